//! Joint-space trajectories for a simulated arm: waypoints joined by cosine-eased
//! moves (zero velocity at every waypoint, smooth in between), optionally looping.
//! Easing is monotone between two waypoints, so a trajectory whose waypoints
//! respect the joint limits respects them at every time.

use super::arm::ArmModel;
use super::error::GuardError;
use std::f64::consts::PI;

/// A joint configuration and the time of the move from it to the next waypoint
/// (for the last waypoint: back to the first, when looping; unused otherwise).
#[derive(Debug, Clone, PartialEq)]
pub struct Waypoint {
    pub positions: Vec<f64>,
    pub duration: f64,
}

/// A validated trajectory.
#[derive(Debug, Clone, PartialEq)]
pub struct Trajectory {
    waypoints: Vec<Waypoint>,
    looping: bool,
    /// Start time of the move out of each waypoint.
    starts: Vec<f64>,
    period: f64,
}

impl Trajectory {
    /// At least one waypoint, all of one length, finite positions, durations
    /// finite and `> 0`.
    pub fn new(waypoints: Vec<Waypoint>, looping: bool) -> Result<Self, GuardError> {
        let first = waypoints.first().ok_or(GuardError::EmptyTrajectory)?;
        let dof = first.positions.len();
        for (index, w) in waypoints.iter().enumerate() {
            if w.positions.len() != dof {
                return Err(GuardError::WaypointLength {
                    index,
                    expected: dof,
                    got: w.positions.len(),
                });
            }
            if let Some(&value) = w.positions.iter().find(|x| !x.is_finite()) {
                return Err(GuardError::NonFinite {
                    what: format!("waypoint {index} position"),
                    value,
                });
            }
            if !(w.duration.is_finite() && w.duration > 0.0) {
                return Err(GuardError::BadDuration {
                    index,
                    duration: w.duration,
                });
            }
        }
        let moves = if looping {
            waypoints.len()
        } else {
            waypoints.len() - 1
        };
        let mut starts = Vec::with_capacity(waypoints.len());
        let mut t = 0.0;
        for w in &waypoints {
            starts.push(t);
            t += w.duration;
        }
        let period = waypoints[..moves].iter().map(|w| w.duration).sum();
        if !f64::is_finite(period) {
            return Err(GuardError::BadDuration {
                index: moves.saturating_sub(1),
                duration: period,
            });
        }
        Ok(Self {
            waypoints,
            looping,
            starts,
            period,
        })
    }

    /// [`Self::new`] plus the arm's checks: one value per actuated joint, each
    /// within its limits.
    pub fn for_arm(
        waypoints: Vec<Waypoint>,
        looping: bool,
        arm: &ArmModel,
    ) -> Result<Self, GuardError> {
        let trajectory = Self::new(waypoints, looping)?;
        trajectory.check_arm(arm)?;
        Ok(trajectory)
    }

    /// Checks the waypoints against the arm's joint count and limits.
    pub fn check_arm(&self, arm: &ArmModel) -> Result<(), GuardError> {
        for (index, w) in self.waypoints.iter().enumerate() {
            if w.positions.len() != arm.dof() {
                return Err(GuardError::WaypointLength {
                    index,
                    expected: arm.dof(),
                    got: w.positions.len(),
                });
            }
            for (joint, (&value, j)) in w.positions.iter().zip(arm.actuated_joints()).enumerate() {
                if let Some(l) = j.limits().filter(|l| !l.contains(value)) {
                    return Err(GuardError::OutsideLimits {
                        index,
                        joint,
                        value,
                        lower: l.lower,
                        upper: l.upper,
                    });
                }
            }
        }
        Ok(())
    }

    pub fn waypoints(&self) -> &[Waypoint] {
        &self.waypoints
    }

    pub fn looping(&self) -> bool {
        self.looping
    }

    /// Joint values per waypoint.
    pub fn dof(&self) -> usize {
        self.waypoints[0].positions.len()
    }

    /// Length of one loop, or of the whole run when not looping (0 for one waypoint).
    pub fn period(&self) -> f64 {
        self.period
    }

    /// Joint values at `time` seconds: looping trajectories repeat with
    /// [`Self::period`] (negative times too); others hold the first waypoint
    /// before 0 and the last after the end.
    pub fn positions_at(&self, time: f64) -> Result<Vec<f64>, GuardError> {
        let mut out = vec![0.0; self.dof()];
        self.positions_at_into(time, &mut out)?;
        Ok(out)
    }

    /// [`Self::positions_at`] into `out` (of length [`Self::dof`]).
    pub fn positions_at_into(&self, time: f64, out: &mut [f64]) -> Result<(), GuardError> {
        if !time.is_finite() {
            return Err(GuardError::BadTime(time));
        }
        if out.len() != self.dof() {
            return Err(GuardError::JointCount {
                expected: self.dof(),
                got: out.len(),
            });
        }
        let n = self.waypoints.len();
        let (from, x) = if self.period <= 0.0 {
            (n - 1, 0.0)
        } else if self.looping {
            let t = time.rem_euclid(self.period);
            self.segment(t, n)
        } else if time >= self.period {
            (n - 1, 0.0)
        } else {
            self.segment(time.max(0.0), n - 1)
        };
        let to = (from + 1) % n;
        let eased = 0.5 - 0.5 * (PI * x).cos();
        let (a, b) = (
            &self.waypoints[from].positions,
            &self.waypoints[to].positions,
        );
        for ((o, &p), &q) in out.iter_mut().zip(a).zip(b) {
            *o = p + (q - p) * eased;
        }
        Ok(())
    }

    /// Joint speeds (rad/s or m/s) at `time`: the derivative of
    /// [`Self::positions_at`], `(q - p) π sin(π x) / 2d` within a move of
    /// duration `d`, and 0 where the trajectory holds still.
    pub fn velocities_at(&self, time: f64) -> Result<Vec<f64>, GuardError> {
        if !time.is_finite() {
            return Err(GuardError::BadTime(time));
        }
        let n = self.waypoints.len();
        let (from, x, moving) = if self.period <= 0.0 {
            (n - 1, 0.0, false)
        } else if self.looping {
            let (i, x) = self.segment(time.rem_euclid(self.period), n);
            (i, x, true)
        } else if time >= self.period || time < 0.0 {
            (n - 1, 0.0, false)
        } else {
            let (i, x) = self.segment(time, n - 1);
            (i, x, true)
        };
        let to = (from + 1) % n;
        let duration = self.waypoints[from].duration;
        let rate = if moving && duration > 0.0 {
            0.5 * PI * (PI * x).sin() / duration
        } else {
            0.0
        };
        let (a, b) = (
            &self.waypoints[from].positions,
            &self.waypoints[to].positions,
        );
        Ok(a.iter().zip(b).map(|(p, q)| (q - p) * rate).collect())
    }

    /// Per joint, the fastest the trajectory moves it: `π |q - p| / 2d` at
    /// the middle of its fastest move.
    pub fn peak_velocities(&self) -> Vec<f64> {
        let n = self.waypoints.len();
        let moves = if self.looping { n } else { n.saturating_sub(1) };
        let mut peak = vec![0.0f64; self.dof()];
        for i in 0..moves {
            let (a, b) = (&self.waypoints[i], &self.waypoints[(i + 1) % n]);
            if a.duration <= 0.0 {
                continue;
            }
            for (k, (p, q)) in a.positions.iter().zip(&b.positions).enumerate() {
                peak[k] = peak[k].max(0.5 * PI * (q - p).abs() / a.duration);
            }
        }
        peak
    }

    /// The move containing `t` (among the first `moves`) and the fraction done.
    fn segment(&self, t: f64, moves: usize) -> (usize, f64) {
        let i = self.starts[..moves]
            .partition_point(|&s| s <= t)
            .saturating_sub(1);
        let x = ((t - self.starts[i]) / self.waypoints[i].duration).clamp(0.0, 1.0);
        (i, x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn velocities_are_the_derivative_and_peak_mid_move() {
        let t = Trajectory::new(vec![wp(&[0.0, 1.0], 2.0), wp(&[1.0, 0.0], 1.0)], true).unwrap();
        assert_eq!(t.peak_velocities(), vec![0.5 * PI, 0.5 * PI]);
        for time in [0.1, 0.7, 1.0, 1.9, 2.3, 2.95, -0.4] {
            let h = 1e-6;
            let (a, b) = (
                t.positions_at(time - h).unwrap(),
                t.positions_at(time + h).unwrap(),
            );
            let v = t.velocities_at(time).unwrap();
            for k in 0..2 {
                let numeric = (b[k] - a[k]) / (2.0 * h);
                assert!(
                    (numeric - v[k]).abs() < 1e-5,
                    "{time}: {numeric} vs {}",
                    v[k]
                );
                assert!(v[k].abs() <= t.peak_velocities()[k] + 1e-12);
            }
        }
        let once = Trajectory::new(vec![wp(&[0.0], 1.0), wp(&[2.0], 1.0)], false).unwrap();
        assert_eq!(once.velocities_at(5.0).unwrap(), vec![0.0]);
        assert_eq!(once.peak_velocities(), vec![PI]);
    }

    fn wp(p: &[f64], d: f64) -> Waypoint {
        Waypoint {
            positions: p.to_vec(),
            duration: d,
        }
    }

    #[test]
    fn hits_waypoints_and_eases_between() {
        let t = Trajectory::new(vec![wp(&[0.0, 1.0], 2.0), wp(&[1.0, -1.0], 1.0)], true).unwrap();
        assert_eq!(t.period(), 3.0);
        assert_eq!(t.positions_at(0.0).unwrap(), vec![0.0, 1.0]);
        assert_eq!(t.positions_at(2.0).unwrap(), vec![1.0, -1.0]);
        let mid = t.positions_at(1.0).unwrap();
        assert!((mid[0] - 0.5).abs() < 1e-12 && mid[1].abs() < 1e-12);
        // The loop comes back and repeats, also for negative times.
        let back = t.positions_at(2.5).unwrap();
        assert!((back[0] - 0.5).abs() < 1e-12);
        assert_eq!(t.positions_at(3.0).unwrap(), vec![0.0, 1.0]);
        let (a, b) = (t.positions_at(-0.5).unwrap(), t.positions_at(2.5).unwrap());
        assert!((a[0] - b[0]).abs() < 1e-12);
        // Slow near waypoints (zero velocity), fastest halfway.
        let near = t.positions_at(0.01).unwrap()[0];
        assert!(near < 0.001);
    }

    #[test]
    fn non_looping_holds_the_ends() {
        let t = Trajectory::new(
            vec![wp(&[0.0], 1.0), wp(&[2.0], 1.0), wp(&[4.0], 9.0)],
            false,
        )
        .unwrap();
        assert_eq!(t.period(), 2.0);
        assert_eq!(t.positions_at(-5.0).unwrap(), vec![0.0]);
        assert_eq!(t.positions_at(1.0).unwrap(), vec![2.0]);
        assert_eq!(t.positions_at(100.0).unwrap(), vec![4.0]);
        let single = Trajectory::new(vec![wp(&[3.0], 1.0)], false).unwrap();
        assert_eq!(single.positions_at(7.0).unwrap(), vec![3.0]);
        let single_loop = Trajectory::new(vec![wp(&[3.0], 1.0)], true).unwrap();
        assert_eq!(single_loop.positions_at(0.3).unwrap(), vec![3.0]);
    }

    #[test]
    fn stays_within_the_waypoint_range() {
        let t = Trajectory::new(vec![wp(&[-1.0], 0.7), wp(&[1.0], 1.3)], true).unwrap();
        for i in 0..1000 {
            let q = t.positions_at(i as f64 * 0.0137).unwrap()[0];
            assert!((-1.0..=1.0).contains(&q), "{q}");
        }
    }

    #[test]
    fn bad_trajectories_are_refused() {
        assert_eq!(
            Trajectory::new(vec![], true),
            Err(GuardError::EmptyTrajectory)
        );
        assert!(matches!(
            Trajectory::new(vec![wp(&[0.0], 1.0), wp(&[0.0, 1.0], 1.0)], true),
            Err(GuardError::WaypointLength { index: 1, .. })
        ));
        assert!(matches!(
            Trajectory::new(vec![wp(&[f64::NAN], 1.0)], true),
            Err(GuardError::NonFinite { .. })
        ));
        for d in [0.0, -1.0, f64::INFINITY, f64::NAN] {
            assert!(matches!(
                Trajectory::new(vec![wp(&[0.0], d)], true),
                Err(GuardError::BadDuration { .. })
            ));
        }
        assert!(matches!(
            Trajectory::new(vec![wp(&[0.0], 1e308), wp(&[0.0], 1e308)], true),
            Err(GuardError::BadDuration { .. })
        ));
        let t = Trajectory::new(vec![wp(&[0.0], 1.0)], true).unwrap();
        assert!(matches!(
            t.positions_at(f64::NAN),
            Err(GuardError::BadTime(_))
        ));
        assert!(t.positions_at(f64::INFINITY).is_err());
        assert!(t.positions_at_into(0.0, &mut [0.0, 0.0]).is_err());
    }
}
