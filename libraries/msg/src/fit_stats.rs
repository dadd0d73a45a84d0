//! Iteration statistics of a fit (the histograms of Figure 9).

use serde::{Deserialize, Serialize};

/// Counts of how often each value occurred (index = value).
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Histogram {
    pub counts: Vec<u64>,
}

impl Histogram {
    pub fn add(&mut self, value: usize) {
        if self.counts.len() <= value {
            self.counts.resize(value + 1, 0);
        }
        self.counts[value] += 1;
    }

    pub fn merge(&mut self, other: &Histogram) {
        for (v, c) in other.counts.iter().enumerate() {
            if *c > 0 {
                if self.counts.len() <= v {
                    self.counts.resize(v + 1, 0);
                }
                self.counts[v] += c;
            }
        }
    }

    pub fn total(&self) -> u64 {
        self.counts.iter().sum()
    }

    pub fn mean(&self) -> f64 {
        let n = self.total();
        if n == 0 {
            return 0.0;
        }
        self.counts
            .iter()
            .enumerate()
            .map(|(v, c)| v as f64 * *c as f64)
            .sum::<f64>()
            / n as f64
    }

    pub fn max(&self) -> usize {
        self.counts.iter().rposition(|&c| c > 0).unwrap_or(0)
    }
}

/// What a fit did, beyond its result.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct FitStats {
    pub points: u64,
    /// Candidate samples kept by the one-pass reduction (all lines, all sides).
    pub candidates: u64,
    /// Solves per line of Heuristic(σ, b, λ) (Figure 9).
    pub curve_solves: Histogram,
    /// Solves per column of Heuristic(σ, b).
    pub column_solves: Histogram,
    pub reselections: u64,
    /// Curve intervals finished by the monotone local raise.
    pub raised_intervals: u64,
    /// Coefficient moves of the tightening pass.
    pub tightening_moves: u64,
    /// Coefficient pairs adjusted so that a sandwich never crosses.
    pub uncrossed_coefficients: u64,
    /// Whether the fit was warm-started from a previous frame.
    pub warm_started: bool,
}

impl FitStats {
    /// Adds what fitting one side of the surrogate counted (its candidates,
    /// solves, reselections, raises and tightening moves).
    pub fn add_side(&mut self, side: &FitStats) {
        self.candidates += side.candidates;
        self.curve_solves.merge(&side.curve_solves);
        self.column_solves.merge(&side.column_solves);
        self.reselections += side.reselections;
        self.raised_intervals += side.raised_intervals;
        self.tightening_moves += side.tightening_moves;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_side_adds_its_counts_and_histograms() {
        let mut side = FitStats {
            candidates: 3,
            reselections: 2,
            raised_intervals: 1,
            tightening_moves: 5,
            ..Default::default()
        };
        side.curve_solves.add(4);
        side.column_solves.add(2);
        let mut total = FitStats {
            points: 10,
            uncrossed_coefficients: 7,
            warm_started: true,
            ..side.clone()
        };
        total.add_side(&side);
        assert_eq!(
            (total.candidates, total.reselections, total.raised_intervals),
            (6, 4, 2)
        );
        assert_eq!(total.tightening_moves, 10);
        assert_eq!(total.curve_solves.counts, vec![0, 0, 0, 0, 2]);
        assert_eq!(total.column_solves.counts, vec![0, 0, 2]);
        // What belongs to the whole fit is not a side's to add.
        assert_eq!(
            (
                total.points,
                total.uncrossed_coefficients,
                total.warm_started
            ),
            (10, 7, true)
        );
    }
}
