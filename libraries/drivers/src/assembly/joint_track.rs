//! The recent angles of a turning mount, as joint-state samples report them:
//! interpolated at any time they bracket, never extrapolated.

use std::collections::VecDeque;
use std::f64::consts::{PI, TAU};

/// Samples kept; at 100 Hz this is 40 s of history.
const CAPACITY: usize = 4096;

/// One sample: its time, the angle unwrapped along the samples (so that a
/// turning joint's angle grows past 2π), and the sweep it belongs to.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Sample {
    unix_ns: u64,
    angle: f64,
    sweep: u64,
}

/// Angle samples in time order. A sweep ends where the motion reverses (a
/// nodding unit) or the unwrapped angle passes a multiple of 2π (a turning
/// one).
#[derive(Debug, Clone)]
pub struct JointTrack {
    samples: VecDeque<Sample>,
    /// Largest time between two samples that may be interpolated across.
    max_gap_ns: u64,
    /// Direction of the last clear motion: +1, -1 or 0 (none yet).
    direction: f64,
}

/// Angular motion below this (radians) between samples is not a direction.
const STILL: f64 = 1e-6;

impl JointTrack {
    pub fn new(max_gap_ns: u64) -> Self {
        Self {
            samples: VecDeque::new(),
            max_gap_ns,
            direction: 0.0,
        }
    }

    /// Adds a sample. Refused (false) unless finite and later than the last.
    pub fn push(&mut self, unix_ns: u64, angle: f64) -> bool {
        if !angle.is_finite() {
            return false;
        }
        let sample = match self.samples.back() {
            None => Sample {
                unix_ns,
                angle,
                sweep: 0,
            },
            Some(last) if unix_ns <= last.unix_ns => return false,
            Some(last) => self.follow(*last, unix_ns, angle),
        };
        if self.samples.len() == CAPACITY {
            self.samples.pop_front();
        }
        self.samples.push_back(sample);
        true
    }

    /// The sample after `last`: angle unwrapped by the shortest arc, sweep
    /// advanced on a reversal or a full turn.
    fn follow(&mut self, last: Sample, unix_ns: u64, angle: f64) -> Sample {
        let step = (angle - last.angle + PI).rem_euclid(TAU) - PI;
        let unwrapped = last.angle + step;
        let mut sweep = last.sweep;
        if step.abs() > STILL {
            let direction = step.signum();
            if self.direction != 0.0 && direction != self.direction {
                sweep += 1;
            }
            self.direction = direction;
        }
        if (unwrapped / TAU).floor() != (last.angle / TAU).floor() {
            sweep += 1;
        }
        Sample {
            unix_ns,
            angle: unwrapped,
            sweep,
        }
    }

    /// Time of the newest sample.
    pub fn latest_ns(&self) -> Option<u64> {
        self.samples.back().map(|s| s.unix_ns)
    }

    /// Time of the oldest sample kept.
    pub fn earliest_ns(&self) -> Option<u64> {
        self.samples.front().map(|s| s.unix_ns)
    }

    /// The angle and sweep at `unix_ns`, interpolated linearly between the
    /// two samples around it; `None` outside the samples or across a gap
    /// longer than the track's limit.
    pub fn at(&self, unix_ns: u64) -> Option<(f64, u64)> {
        let after = self.samples.partition_point(|s| s.unix_ns < unix_ns);
        let b = self.samples.get(after)?;
        if b.unix_ns == unix_ns {
            return Some((b.angle, b.sweep));
        }
        let a = self.samples.get(after.checked_sub(1)?)?;
        if b.unix_ns - a.unix_ns > self.max_gap_ns {
            return None;
        }
        let f = (unix_ns - a.unix_ns) as f64 / (b.unix_ns - a.unix_ns) as f64;
        Some((a.angle + f * (b.angle - a.angle), a.sweep))
    }

    /// The largest difference between the angle at `at` and any angle over
    /// `[from, to]` (the track is linear between samples, so the extremes
    /// are at the ends or at samples); `None` unless the samples cover
    /// both ends.
    pub fn max_deviation(&self, at: u64, from: u64, to: u64) -> Option<f64> {
        let (reference, _) = self.at(at)?;
        let (start, _) = self.at(from)?;
        let (end, _) = self.at(to)?;
        let first = self.samples.partition_point(|s| s.unix_ns <= from);
        let inside: Vec<&Sample> = self
            .samples
            .range(first..)
            .take_while(|s| s.unix_ns < to)
            .collect();
        // No gap too long to interpolate across between the ends.
        let mut previous = from;
        for s in &inside {
            if s.unix_ns - previous > self.max_gap_ns {
                return None;
            }
            previous = s.unix_ns;
        }
        let deviation = [start, end]
            .into_iter()
            .chain(inside.iter().map(|s| s.angle))
            .map(|a| (a - reference).abs())
            .fold(0.0, f64::max);
        Some(deviation)
    }
}
