//! Thinning a cloud to a point budget: evenly spaced indices, the same for the
//! same sizes, so that a viewer's cloud does not shimmer from frame to frame.

/// The indices `floor(i * total / kept)` for `i < kept`, where `kept` is
/// `min(total, budget)`: every point when the cloud fits the budget, else an
/// even stride through it (sensors emit points in scan order, so an even stride
/// keeps the scan's coverage).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Decimation {
    total: usize,
    kept: usize,
}

impl Decimation {
    pub fn new(total: usize, budget: usize) -> Self {
        Self {
            total,
            kept: total.min(budget),
        }
    }

    /// How many points are kept.
    pub fn kept(&self) -> usize {
        self.kept
    }

    pub fn total(&self) -> usize {
        self.total
    }

    /// The kept indices, increasing, each below `total`.
    pub fn indices(&self) -> impl ExactSizeIterator<Item = usize> + '_ {
        let (total, kept) = (self.total as u128, self.kept as u128);
        (0..self.kept).map(move |i| (i as u128 * total / kept) as usize)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keeps_everything_within_the_budget_and_strides_evenly_beyond() {
        let all: Vec<usize> = Decimation::new(5, 10).indices().collect();
        assert_eq!(all, vec![0, 1, 2, 3, 4]);
        let half: Vec<usize> = Decimation::new(10, 5).indices().collect();
        assert_eq!(half, vec![0, 2, 4, 6, 8]);
        assert_eq!(Decimation::new(0, 5).indices().count(), 0);
        assert_eq!(Decimation::new(7, 0).indices().count(), 0);
    }

    #[test]
    fn indices_are_strictly_increasing_and_in_range() {
        for total in [1usize, 2, 3, 17, 1000, 300_001] {
            for budget in [1usize, 2, 5, 999, 60_000, 1 << 20] {
                let d = Decimation::new(total, budget);
                let idx: Vec<usize> = d.indices().collect();
                assert_eq!(idx.len(), total.min(budget));
                assert!(idx.windows(2).all(|w| w[0] < w[1]), "{total} {budget}");
                assert!(idx.iter().all(|&i| i < total));
                // Gaps never exceed the ceiling of the stride.
                let stride = total.div_ceil(idx.len().max(1));
                assert!(idx.windows(2).all(|w| w[1] - w[0] <= stride));
            }
        }
    }
}
