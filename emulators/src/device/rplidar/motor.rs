//! The scan motor: its rotation angle over time as it ramps to the speed the
//! host asked for (the real motor takes about half a second to spin up or
//! down; output waits for stable rotation, protocol PDF §3 "Scanning
//! Status").
//!
//! The state is a checkpoint (time, phase, speed) taken at the last change of
//! target speed; the phase at any later time follows in closed form, so the
//! scan stream can ask for angles in any order.

/// Seconds the motor takes to go from rest to its nominal speed; speed
/// changes ramp linearly at nominal / this per second.
pub(crate) const SPIN_UP_S: f64 = 0.5;

#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Motor {
    since: f64,
    /// Turns in [0, 1) at `since`; clockwise, 0 = the device's 0°.
    phase: f64,
    speed_hz: f64,
    target_hz: f64,
    ramp_hz_per_s: f64,
}

impl Motor {
    /// A motor at rest at time 0, heading for `target_hz`.
    pub(crate) fn new(nominal_hz: f64, target_hz: f64) -> Self {
        Self {
            since: 0.0,
            phase: 0.0,
            speed_hz: 0.0,
            target_hz: target_hz.max(0.0),
            ramp_hz_per_s: nominal_hz / SPIN_UP_S,
        }
    }

    pub(crate) fn target_hz(&self) -> f64 {
        self.target_hz
    }

    /// Heads for `target_hz` from `now` on (`now` not before the last change).
    pub(crate) fn set_target(&mut self, target_hz: f64, now: f64) {
        let now = now.max(self.since);
        self.phase = self.phase_at(now);
        self.speed_hz = self.speed_at(now);
        self.since = now;
        self.target_hz = target_hz.max(0.0);
    }

    /// When the ramp to the target ends.
    fn ramp_end(&self) -> f64 {
        let gap = (self.target_hz - self.speed_hz).abs();
        if gap == 0.0 || self.ramp_hz_per_s <= 0.0 {
            self.since
        } else {
            self.since + gap / self.ramp_hz_per_s
        }
    }

    /// Rotation speed at `t` (times before the last change read as it).
    pub(crate) fn speed_at(&self, t: f64) -> f64 {
        let end = self.ramp_end();
        if t >= end {
            return self.target_hz;
        }
        let ramped = self.ramp_hz_per_s * (t - self.since).max(0.0);
        if self.target_hz > self.speed_hz {
            self.speed_hz + ramped
        } else {
            self.speed_hz - ramped
        }
    }

    /// Turns in [0, 1) at `t`.
    pub(crate) fn phase_at(&self, t: f64) -> f64 {
        let t = t.max(self.since);
        let end = self.ramp_end();
        let ramp_time = t.min(end) - self.since;
        let ramp_turns = 0.5 * (self.speed_hz + self.speed_at(self.since + ramp_time)) * ramp_time;
        let steady_turns = self.target_hz * (t - end).max(0.0);
        (self.phase + ramp_turns + steady_turns).rem_euclid(1.0)
    }

    /// Clockwise degrees in [0, 360) at `t`.
    pub(crate) fn angle_deg_at(&self, t: f64) -> f64 {
        self.phase_at(t) * 360.0
    }

    /// Turning at its (non-zero) target speed at `t`.
    pub(crate) fn is_stable_at(&self, t: f64) -> bool {
        self.target_hz > 0.0 && t >= self.ramp_end()
    }

    /// When rotation becomes stable, or `None` while the target is rest.
    pub(crate) fn stable_from(&self) -> Option<f64> {
        (self.target_hz > 0.0).then(|| self.ramp_end())
    }
}
