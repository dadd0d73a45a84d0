//! A configured sweep of a turning mount: its angle as a function of time,
//! locked to the Unix epoch so that a unit and every node reading it agree on
//! the phase without talking to each other.

use super::error::AssemblyError;
use std::f64::consts::{PI, TAU};
use std::str::FromStr;

/// A periodic mount angle. `t` below is the wall-clock time modulo the period,
/// so the phase is the same in every process on hosts whose clocks agree.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SweepProfile {
    /// Nods between `center ± amplitude` (radians):
    /// `center + amplitude * sin(2π t / period)`.
    Sine {
        center: f64,
        amplitude: f64,
        period_ns: u64,
    },
    /// Nods at constant speed between `center ± amplitude`: at the lower
    /// extreme at `t = 0`, at the upper one at half the period.
    Triangle {
        center: f64,
        amplitude: f64,
        period_ns: u64,
    },
    /// Turns at constant speed: `2π t / period`, in [0, 2π).
    Rotate { period_ns: u64 },
}

impl SweepProfile {
    fn period_ns(&self) -> u64 {
        match *self {
            Self::Sine { period_ns, .. }
            | Self::Triangle { period_ns, .. }
            | Self::Rotate { period_ns } => period_ns,
        }
    }

    /// The phase at `unix_ns`, in [0, 1).
    fn phase(&self, unix_ns: u64) -> f64 {
        let period = self.period_ns();
        (unix_ns % period) as f64 / period as f64
    }

    /// The mount angle (radians) at `unix_ns`.
    pub fn angle_at(&self, unix_ns: u64) -> f64 {
        let phase = self.phase(unix_ns);
        match *self {
            Self::Sine {
                center, amplitude, ..
            } => center + amplitude * (TAU * phase).sin(),
            Self::Triangle {
                center, amplitude, ..
            } => {
                // -1 at phase 0, +1 at phase 1/2, back to -1.
                let wave = if phase < 0.5 {
                    4.0 * phase - 1.0
                } else {
                    3.0 - 4.0 * phase
                };
                center + amplitude * wave
            }
            Self::Rotate { .. } => TAU * phase,
        }
    }

    /// Which sweep `unix_ns` falls in: a nodding mount sweeps from one extreme
    /// to the other (two sweeps a period), a turning one once a turn. Sweep
    /// numbers grow by one at each boundary.
    pub fn sweep_index(&self, unix_ns: u64) -> u64 {
        let period = self.period_ns();
        match self {
            // Extremes of the sine are at a quarter and three quarters.
            Self::Sine { .. } => {
                ((2 * unix_ns as u128 + period as u128 / 2) / period as u128) as u64
            }
            Self::Triangle { .. } => ((2 * unix_ns as u128) / period as u128) as u64,
            Self::Rotate { .. } => unix_ns / period,
        }
    }

    /// The largest angular speed of the mount (radians a second).
    pub fn max_speed(&self) -> f64 {
        let period_s = self.period_ns() as f64 * 1e-9;
        match *self {
            Self::Sine { amplitude, .. } => amplitude.abs() * TAU / period_s,
            Self::Triangle { amplitude, .. } => 4.0 * amplitude.abs() / period_s,
            Self::Rotate { .. } => TAU / period_s,
        }
    }
}

fn number(text: &str, field: &str, whole: &str) -> Result<f64, AssemblyError> {
    let value: f64 = field
        .parse()
        .map_err(|e| AssemblyError::parse("sweep profile", whole, format!("{field:?}: {e}")))?;
    if !value.is_finite() {
        return Err(AssemblyError::parse(
            "sweep profile",
            whole,
            format!("{text} {value} is not finite"),
        ));
    }
    Ok(value)
}

impl FromStr for SweepProfile {
    type Err = AssemblyError;

    /// `sine:AMPLITUDE_DEG:PERIOD_S[:CENTER_DEG]`,
    /// `triangle:AMPLITUDE_DEG:PERIOD_S[:CENTER_DEG]` or `rotate:PERIOD_S`.
    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let fields: Vec<&str> = text.split(':').collect();
        let bad = |reason: &str| AssemblyError::parse("sweep profile", text, reason);
        let period = |field: &str| -> Result<u64, AssemblyError> {
            let seconds = number("period", field, text)?;
            if !(1e-3..=86_400.0).contains(&seconds) {
                return Err(bad("the period must be between 1 ms and a day"));
            }
            Ok((seconds * 1e9).round() as u64)
        };
        match fields.as_slice() {
            ["rotate", p] => Ok(Self::Rotate {
                period_ns: period(p)?,
            }),
            [kind @ ("sine" | "triangle"), a, p, rest @ ..] if rest.len() <= 1 => {
                let amplitude = number("amplitude", a, text)?.to_radians();
                if !(amplitude > 0.0 && amplitude <= PI) {
                    return Err(bad("the amplitude must be in (0, 180] degrees"));
                }
                let center = match rest {
                    [c] => number("center", c, text)?.to_radians(),
                    _ => 0.0,
                };
                let period_ns = period(p)?;
                Ok(if *kind == "sine" {
                    Self::Sine {
                        center,
                        amplitude,
                        period_ns,
                    }
                } else {
                    Self::Triangle {
                        center,
                        amplitude,
                        period_ns,
                    }
                })
            }
            _ => Err(bad(
                "expected sine:AMPLITUDE_DEG:PERIOD_S[:CENTER_DEG], \
                 triangle:AMPLITUDE_DEG:PERIOD_S[:CENTER_DEG] or rotate:PERIOD_S",
            )),
        }
    }
}
