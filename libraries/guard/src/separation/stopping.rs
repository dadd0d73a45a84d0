//! How far and how long one joint takes to stop from a speed: a constant
//! deceleration, or stops measured at fractions of the velocity limit as
//! ISO 10218-1 (Annex B) asks makers to publish.

use crate::GuardError;

/// One joint's stop: travel (radians or metres) and time (seconds).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Stop {
    pub distance: f64,
    pub time: f64,
}

/// A measured stop: from `fraction` of the joint's velocity limit, the joint
/// travelled `distance` and took `time`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StopSample {
    pub fraction: f64,
    pub distance: f64,
    pub time: f64,
}

/// A joint's stopping behaviour.
#[derive(Debug, Clone, PartialEq)]
pub enum StoppingModel {
    /// Braking at least this hard (rad/s² or m/s², `> 0`): from speed `v`
    /// the joint travels `v² / 2a` in `v / a`.
    Deceleration(f64),
    /// Measured stops, by increasing fraction, the last at 1 (full speed).
    /// A speed between two samples takes the faster one's stop: the table is
    /// never interpolated downwards.
    Measured(Vec<StopSample>),
}

impl StoppingModel {
    /// Checks the numbers: a finite positive deceleration, or samples with
    /// fractions rising in (0, 1] and ending at 1, distances and times finite,
    /// `>= 0` and not decreasing with speed (a faster stop that is shorter is a
    /// measurement error, and the lookup relies on it).
    pub fn validate(&self, joint: &str) -> Result<(), GuardError> {
        let bad = |m: String| Err(GuardError::BadConfig(format!("joint '{joint}': {m}")));
        match self {
            Self::Deceleration(a) if !(a.is_finite() && *a > 0.0) => {
                bad(format!("deceleration must be finite and > 0, got {a}"))
            }
            Self::Deceleration(_) => Ok(()),
            Self::Measured(samples) => {
                let Some(last) = samples.last() else {
                    return bad("the stopping table is empty".into());
                };
                if last.fraction != 1.0 {
                    return bad(format!(
                        "the stopping table must end at fraction 1 (full speed), ends at {}",
                        last.fraction
                    ));
                }
                let mut previous = StopSample {
                    fraction: 0.0,
                    distance: 0.0,
                    time: 0.0,
                };
                for s in samples {
                    let finite = s.distance.is_finite() && s.time.is_finite();
                    if !(s.fraction > previous.fraction && finite) {
                        return bad(format!(
                            "stopping table fractions must rise in (0, 1] with finite values, got {s:?}"
                        ));
                    }
                    if !(s.distance >= previous.distance && s.time >= previous.time) {
                        return bad(format!(
                            "a stop from a higher speed must not be shorter or quicker: {s:?} after {previous:?}"
                        ));
                    }
                    previous = *s;
                }
                Ok(())
            }
        }
    }

    /// Slowing from `from` to `to` (`0 <= to < from`): exact under a constant
    /// deceleration; from a table, the whole stop from `from` (braking speed
    /// falls monotonically, so it passes `to` before it stops).
    pub fn slow(&self, from: f64, to: f64, max_velocity: f64) -> Stop {
        match self {
            Self::Deceleration(a) if from > to => Stop {
                distance: (from * from - to * to) / (2.0 * a),
                time: (from - to) / a,
            },
            Self::Deceleration(_) => Stop::default(),
            Self::Measured(_) => self.stop(from, max_velocity),
        }
    }

    /// The stop from `speed` (`>= 0`) for a joint whose velocity limit is
    /// `max_velocity`. A measured table is looked up at the first sample at or
    /// above `speed / max_velocity`; above full speed, where nothing was
    /// measured, its full-speed stop is scaled as a constant deceleration
    /// would scale it (distance with the square of the speed, time linearly).
    pub fn stop(&self, speed: f64, max_velocity: f64) -> Stop {
        let speed = speed.abs();
        if speed == 0.0 {
            return Stop::default();
        }
        match self {
            Self::Deceleration(a) => Stop {
                distance: speed * speed / (2.0 * a),
                time: speed / a,
            },
            Self::Measured(samples) => {
                let fraction = speed / max_velocity;
                if let Some(s) = samples.iter().find(|s| s.fraction >= fraction) {
                    return Stop {
                        distance: s.distance,
                        time: s.time,
                    };
                }
                let full = samples.last().copied().unwrap_or(StopSample {
                    fraction: 1.0,
                    distance: f64::INFINITY,
                    time: f64::INFINITY,
                });
                Stop {
                    distance: full.distance * fraction * fraction,
                    time: full.time * fraction,
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table() -> StoppingModel {
        StoppingModel::Measured(vec![
            StopSample {
                fraction: 0.33,
                distance: 0.05,
                time: 0.1,
            },
            StopSample {
                fraction: 0.66,
                distance: 0.15,
                time: 0.2,
            },
            StopSample {
                fraction: 1.0,
                distance: 0.31,
                time: 0.244,
            },
        ])
    }

    #[test]
    fn deceleration_stops_as_kinematics_says() {
        let s = StoppingModel::Deceleration(4.0).stop(2.0, 3.0);
        assert_eq!((s.distance, s.time), (0.5, 0.5));
        assert_eq!(
            StoppingModel::Deceleration(4.0).stop(0.0, 3.0),
            Stop::default()
        );
        let slow = StoppingModel::Deceleration(4.0).slow(2.0, 1.0, 3.0);
        assert_eq!((slow.distance, slow.time), (0.375, 0.25));
    }

    #[test]
    fn a_table_is_read_at_the_next_faster_sample() {
        let t = table();
        assert!(t.validate("j").is_ok());
        assert_eq!(t.stop(0.1, 1.0).distance, 0.05);
        assert_eq!(t.stop(0.34, 1.0).distance, 0.15);
        assert_eq!(t.stop(0.66, 1.0).distance, 0.15);
        assert_eq!(t.stop(1.0, 1.0).distance, 0.31);
        // Above full speed: scaled as by a constant deceleration.
        let over = t.stop(2.0, 1.0);
        assert_eq!((over.distance, over.time), (0.31 * 4.0, 0.488));
    }

    #[test]
    fn bad_models_are_refused_with_the_joint_named() {
        let refused = |m: StoppingModel| m.validate("elbow").unwrap_err().to_string();
        assert!(refused(StoppingModel::Deceleration(0.0)).contains("elbow"));
        assert!(refused(StoppingModel::Deceleration(f64::NAN)).contains("deceleration"));
        assert!(refused(StoppingModel::Measured(vec![])).contains("empty"));
        let StoppingModel::Measured(mut s) = table() else {
            unreachable!()
        };
        s[2].fraction = 0.9;
        assert!(refused(StoppingModel::Measured(s.clone())).contains("end at fraction 1"));
        s[2].fraction = 1.0;
        s[1].distance = 0.01;
        assert!(refused(StoppingModel::Measured(s.clone())).contains("shorter"));
        s[1].distance = 0.15;
        s[1].fraction = 0.2;
        assert!(refused(StoppingModel::Measured(s)).contains("rise"));
    }
}
