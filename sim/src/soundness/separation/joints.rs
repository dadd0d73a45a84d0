//! The simulated arm's joints: each follows its reference within its speed
//! cap, and when the cap falls below its speed it slows exactly as its
//! stopping model's worst case, never harder.
//!
//! Over one sub-step a joint's speed is `max(floor, m0 - decel · max(0, x -
//! c))` (its sign fixed): constant while it tracks (`decel = 0`), and while
//! it brakes first constant until `c` (a measured table's cruise), then
//! falling at `decel` down to the cap. Positions are the exact integral, so
//! the truth can evaluate the arm at any instant of the sub-step.
//!
//! Braking from speed `v` with a stopping model whose stop from `v` is
//! `(D, T)` (`StoppingModel::stop`, the model the guard reads): a constant
//! deceleration `a` brakes at exactly `a` (`D = v² / 2a`, `T = v / a`); a
//! measured table travels exactly `D` in at most `T`: cruising at `v` for
//! `2D/v - T` and then decelerating uniformly to rest at `T` when `D >= vT/2`
//! (the slowest stop the table allows), decelerating at `v² / 2D` when `D <
//! vT/2`, and cruising `T` then stopping at once when the table's `D` is more
//! than `vT` (below the table's next sample). Slowing to a lower cap
//! follows the same profile until it reaches the cap.

use shroud_guard::StoppingModel;

/// How the simulated arm treats the guard.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ArmBehaviour {
    /// The contract and no better: the scale in force, the reaction time,
    /// the deadman, the stopping model's worst case.
    Obeys,
    /// Negative control: runs its trajectory at full speed whenever its
    /// deadman lets it move at all (a halt and braking are still obeyed).
    IgnoresScale,
    /// Negative control: obeys this many seconds later than its declared
    /// reaction time allows.
    Late(f64),
    /// Negative control: its stops take this many times the distance and
    /// the time its stopping model says.
    SoftBrakes(f64),
}

/// A brake in progress: cruising until `cruise_end`, then decelerating.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Brake {
    cruise_end: f64,
    decel: f64,
}

impl Brake {
    /// The worst-case stop from `speed` (`> 0`) starting at `t0` (see the
    /// module documentation), the model's distance and time times `soften`.
    fn start(t0: f64, speed: f64, model: &StoppingModel, max_velocity: f64, soften: f64) -> Self {
        if let StoppingModel::Deceleration(a) = model {
            return Self {
                cruise_end: t0,
                decel: a / soften,
            };
        }
        let stop = model.stop(speed, max_velocity);
        let (d, t) = (stop.distance * soften, stop.time * soften);
        if !(d > 0.0 && t > 0.0) {
            return Self {
                cruise_end: t0,
                decel: f64::INFINITY,
            };
        }
        if 2.0 * d <= speed * t {
            Self {
                cruise_end: t0,
                decel: speed * speed / (2.0 * d),
            }
        } else if d < speed * t {
            let cruise = 2.0 * d / speed - t;
            Self {
                cruise_end: t0 + cruise,
                decel: speed / (t - cruise),
            }
        } else {
            Self {
                cruise_end: t0 + t,
                decel: f64::INFINITY,
            }
        }
    }
}

/// One joint's motion over one sub-step starting at `t0` (seconds).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    t0: f64,
    q0: f64,
    sign: f64,
    /// Speed at `t0`, the largest over the sub-step.
    m0: f64,
    /// When the deceleration starts (absolute; before `t0`: already).
    c: f64,
    decel: f64,
    /// The speed it decelerates to (the cap), `<= m0`.
    floor: f64,
}

impl Segment {
    /// The largest speed over the sub-step (at its start).
    pub fn max_speed(&self) -> f64 {
        self.m0
    }

    /// Seconds from `t0` to the start of the deceleration, and the
    /// deceleration's length, when it decelerates at all.
    fn phases(&self) -> Option<(f64, f64)> {
        if self.decel <= 0.0 || self.m0 <= self.floor {
            return None;
        }
        let cruise = (self.c - self.t0).max(0.0);
        let fall = if self.decel.is_infinite() {
            0.0
        } else {
            (self.m0 - self.floor) / self.decel
        };
        Some((cruise, fall))
    }

    /// Speed at `x` (within the sub-step).
    pub fn speed(&self, x: f64) -> f64 {
        let dt = x - self.t0;
        match self.phases() {
            None => self.m0,
            Some((cruise, _)) if dt <= cruise => self.m0,
            Some(_) if self.decel.is_infinite() => self.floor,
            Some((cruise, _)) => (self.m0 - self.decel * (dt - cruise)).max(self.floor),
        }
    }

    /// Signed velocity at `x`.
    pub fn velocity(&self, x: f64) -> f64 {
        self.sign * self.speed(x)
    }

    /// Position at `x` (within the sub-step): the exact integral.
    pub fn position(&self, x: f64) -> f64 {
        let dt = (x - self.t0).max(0.0);
        let travel = match self.phases() {
            None => self.m0 * dt,
            Some((cruise, _)) if dt <= cruise => self.m0 * dt,
            Some((cruise, fall)) => {
                let y = dt - cruise;
                if y <= fall {
                    self.m0 * cruise + self.m0 * y - 0.5 * self.decel * y * y
                } else {
                    self.m0 * cruise + 0.5 * (self.m0 + self.floor) * fall + self.floor * (y - fall)
                }
            }
        };
        self.q0 + self.sign * travel
    }
}

/// One simulated joint.
#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    pub q: f64,
    pub v: f64,
    brake: Option<Brake>,
}

/// Relative slack before a speed counts as over its cap (rounding only).
const OVER_CAP: f64 = 1e-12;

impl Joint {
    pub fn at_rest(q: f64) -> Self {
        Self {
            q,
            v: 0.0,
            brake: None,
        }
    }

    /// The motion over a sub-step from `t0` with speed cap `cap` (`>= 0`)
    /// and the velocity the controller wants, `desired`: braking while the
    /// speed is over the cap (the worst case of `model`, scaled by
    /// `soften`), else `desired` clamped to the cap, held over the sub-step.
    pub fn plan(
        &mut self,
        t0: f64,
        cap: f64,
        desired: f64,
        model: &StoppingModel,
        max_velocity: f64,
        soften: f64,
    ) -> Segment {
        let speed = self.v.abs();
        if speed > cap * (1.0 + OVER_CAP) + OVER_CAP {
            let brake = *self
                .brake
                .get_or_insert_with(|| Brake::start(t0, speed, model, max_velocity, soften));
            return Segment {
                t0,
                q0: self.q,
                sign: self.v.signum(),
                m0: speed,
                c: brake.cruise_end,
                decel: brake.decel,
                floor: cap,
            };
        }
        self.brake = None;
        let v = desired.clamp(-cap, cap);
        Segment {
            t0,
            q0: self.q,
            sign: if v < 0.0 { -1.0 } else { 1.0 },
            m0: v.abs(),
            c: t0,
            decel: 0.0,
            floor: v.abs(),
        }
    }

    /// Moves to the end `t1` of the sub-step `segment` planned.
    pub fn finish(&mut self, segment: &Segment, t1: f64) {
        self.q = segment.position(t1);
        self.v = segment.velocity(t1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use shroud_guard::StopSample;

    /// Integrates a joint braking from `v0` to rest in small sub-steps and
    /// returns the distance and time it took.
    fn brake_run(model: &StoppingModel, max_velocity: f64, v0: f64, soften: f64) -> (f64, f64) {
        let mut j = Joint {
            q: 0.0,
            v: v0,
            brake: None,
        };
        let (mut t, h) = (0.0, 1e-4);
        while j.v != 0.0 {
            let s = j.plan(t, 0.0, 0.0, model, max_velocity, soften);
            // Sub-step boundaries may fall anywhere: check the integral
            // against a fine sum inside the sub-step too.
            let mid = s.position(t + h / 2.0);
            assert!((mid - s.q0).abs() <= s.max_speed() * h / 2.0 + 1e-15);
            j.finish(&s, t + h);
            t += h;
            assert!(t < 10.0, "never stopped");
        }
        (j.q.abs(), t)
    }

    #[test]
    fn a_constant_deceleration_brakes_at_exactly_its_rate() {
        let model = StoppingModel::Deceleration(4.0);
        let (d, t) = brake_run(&model, 2.0, 2.0, 1.0);
        // v²/2a = 0.5 m in v/a = 0.5 s (to within a sub-step).
        assert!((d - 0.5).abs() < 1e-9, "{d}");
        assert!((t - 0.5).abs() <= 1e-4 + 1e-9, "{t}");
        let (soft, _) = brake_run(&model, 2.0, 2.0, 2.0);
        assert!((soft - 1.0).abs() < 1e-9, "{soft}");
    }

    #[test]
    fn a_measured_stop_uses_the_whole_distance_and_no_more_time() {
        let model = StoppingModel::Measured(vec![
            StopSample {
                fraction: 0.5,
                distance: 0.2,
                time: 0.3,
            },
            StopSample {
                fraction: 1.0,
                distance: 0.5,
                time: 0.6,
            },
        ]);
        for (v0, want) in [(1.0, (0.5, 0.6)), (0.9, (0.5, 0.6)), (0.4, (0.2, 0.3))] {
            let (d, t) = brake_run(&model, 1.0, v0, 1.0);
            let (dist, time) = want;
            // D <= vT: exactly D; D > vT (a speed well below the sample):
            // at most vT, cruising the whole time.
            let expect = f64::min(dist, v0 * time);
            assert!((d - expect).abs() < 1e-9, "{v0}: {d} vs {expect}");
            assert!(t <= time + 1e-4 + 1e-9, "{v0}: {t} > {time}");
        }
    }

    #[test]
    fn slowing_stops_at_the_cap_and_tracking_respects_it() {
        let model = StoppingModel::Deceleration(10.0);
        let mut j = Joint {
            q: 0.0,
            v: -1.0,
            brake: None,
        };
        let s = j.plan(0.0, 0.4, 0.0, &model, 1.0, 1.0);
        // From 1 to 0.4 at 10 takes 0.06 s and (1 - 0.16) / 20 = 0.042.
        j.finish(&s, 0.1);
        assert!((j.v + 0.4).abs() < 1e-12, "{}", j.v);
        assert!((j.q + 0.042 + 0.4 * 0.04).abs() < 1e-12, "{}", j.q);
        let s = j.plan(0.1, 0.4, 3.0, &model, 1.0, 1.0);
        assert_eq!(s.max_speed(), 0.4);
        assert_eq!(s.velocity(0.15), 0.4);
    }
}
