//! Nearest-rank percentiles over a bounded window of samples.

use serde::Serialize;

/// Keeps the last `capacity` samples (a ring) and answers percentiles over them.
#[derive(Debug, Clone)]
pub struct Percentiles {
    samples: Vec<f64>,
    next: usize,
    capacity: usize,
    total: u64,
}

/// p50 / p99 / max over a window, plus how many samples it holds.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LatencySummary {
    pub count: usize,
    pub p50: f64,
    pub p99: f64,
    pub max: f64,
    pub mean: f64,
}

impl Percentiles {
    pub fn new(capacity: usize) -> Self {
        let capacity = capacity.max(1);
        Self {
            samples: Vec::with_capacity(capacity),
            next: 0,
            capacity,
            total: 0,
        }
    }

    /// Adds a sample; non-finite samples are ignored (a clock glitch must not
    /// poison every later percentile).
    pub fn push(&mut self, value: f64) {
        if !value.is_finite() {
            return;
        }
        self.total += 1;
        if self.samples.len() < self.capacity {
            self.samples.push(value);
        } else {
            self.samples[self.next] = value;
        }
        self.next = (self.next + 1) % self.capacity;
    }

    /// Samples pushed since creation, including those that left the window.
    pub fn total(&self) -> u64 {
        self.total
    }

    /// Nearest-rank percentile `q` in [0, 1]; `None` when empty.
    pub fn quantile(&self, q: f64) -> Option<f64> {
        let mut sorted = self.samples.clone();
        sorted.sort_by(f64::total_cmp);
        nearest_rank(&sorted, q)
    }

    pub fn summary(&self) -> Option<LatencySummary> {
        let mut sorted = self.samples.clone();
        sorted.sort_by(f64::total_cmp);
        Some(LatencySummary {
            count: sorted.len(),
            p50: nearest_rank(&sorted, 0.5)?,
            p99: nearest_rank(&sorted, 0.99)?,
            max: *sorted.last()?,
            mean: sorted.iter().sum::<f64>() / sorted.len() as f64,
        })
    }
}

fn nearest_rank(sorted: &[f64], q: f64) -> Option<f64> {
    if sorted.is_empty() {
        return None;
    }
    let q = q.clamp(0.0, 1.0);
    let rank = (q * sorted.len() as f64).ceil() as usize;
    sorted.get(rank.saturating_sub(1)).copied()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearest_rank_on_known_data() {
        let mut p = Percentiles::new(1000);
        for v in (1..=100).rev() {
            p.push(v as f64);
        }
        p.push(f64::NAN);
        let s = p.summary().unwrap();
        assert_eq!((s.count, s.p50, s.p99, s.max), (100, 50.0, 99.0, 100.0));
        assert_eq!(p.quantile(0.0), Some(1.0));
        assert!(Percentiles::new(4).summary().is_none());
    }

    #[test]
    fn the_window_forgets_old_samples() {
        let mut p = Percentiles::new(3);
        for v in [100.0, 1.0, 2.0, 3.0] {
            p.push(v);
        }
        assert_eq!(p.summary().unwrap().max, 3.0);
        assert_eq!(p.total(), 4);
    }
}
