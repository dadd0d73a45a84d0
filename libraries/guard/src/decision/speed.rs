//! Speed and separation monitoring in the decision: after the clearances,
//! the largest speed scale every link allows ([`SpeedMonitor`]), limited in
//! its rise ([`ScaleGovernor`]); a scale of 0 turns `clear` into `stop`.

use super::decider::{CollisionGuard, Decision};
use super::speed_control::SpeedControl;
use crate::{GuardError, MotionNow, ScaleGovernor, SpeedMonitor, SpeedScale, Timing, WorldShape};
use shroud_msg::{counted_transit, GuardVerdict};

/// What the guard knows of the arm's motion at a joint state.
#[derive(Debug, Clone, Copy, Default)]
pub struct JointMotionSample<'a> {
    /// Measured joint speeds, one per actuated joint, if the state had them.
    pub velocities: Option<&'a [f64]>,
    /// Nanoseconds from the joint state's sample to the decision, on the
    /// guard's clocks (its transit, bounded as the views' transit is).
    pub age_ns: u64,
}

impl CollisionGuard {
    /// Scales the arm's speed from now on (ISO/TS 15066 speed and separation
    /// monitoring). Clearances are then computed up to the largest protective
    /// distance any link can need at full speed, after the motion allowance,
    /// so that scale 1 is reachable.
    pub fn with_speed_monitor(mut self, monitor: SpeedMonitor) -> Self {
        let timing = self.timing();
        let reach = self.config.max_obstacle_speed
            * (self.policy.max_age_ns as f64 * 1e-9 + self.config.horizon);
        let need = monitor.largest_need(self.config.stop_distance, &timing) + reach;
        self.config.max_report = self.config.max_report.max(need);
        let governor = ScaleGovernor::new(
            monitor.motion().scale_rise_per_second,
            monitor.window(self.config.horizon),
        );
        debug_assert_eq!(monitor.links(), self.links.len());
        self.speed = Some(SpeedControl { monitor, governor });
        self
    }

    /// How old a joint state is at `now_ns` (monotonic): its transit from
    /// publication (`published_ns`, the publisher's wall clock) to its
    /// arrival (`received_wall_ns`), counted with the clock offset bound as a
    /// surrogate's is, plus the time since it arrived (`received_ns`,
    /// monotonic). Without a publication stamp, or from further in the future
    /// than the offset bound, its age cannot be told: speed monitoring then
    /// refuses it (the caller answers with a stop).
    pub fn joint_state_age_ns(
        &self,
        published_ns: Option<u64>,
        received_wall_ns: u64,
        received_ns: u64,
        now_ns: u64,
    ) -> Result<u64, GuardError> {
        let published = published_ns.ok_or_else(|| {
            GuardError::JointStateTiming("no publication stamp: its age is unknown".into())
        })?;
        let transit = counted_transit(published, received_wall_ns, self.policy.max_clock_offset_ns)
            .map_err(|e| GuardError::JointStateTiming(e.to_string()))?;
        Ok(transit.saturating_add(now_ns.saturating_sub(received_ns)))
    }

    /// Whether the guard scales the arm's speed.
    pub fn monitors_speed(&self) -> bool {
        self.speed.is_some()
    }

    fn timing(&self) -> Timing {
        Timing {
            horizon: self.config.horizon,
            obstacle_speed: self.config.max_obstacle_speed,
        }
    }

    /// [`Self::decide`], then the speed scale: without a monitor, 1 for
    /// `clear` and 0 otherwise; with one, the largest scale every link
    /// allows after the rise limit, and `stop` where it is 0, where a joint
    /// is measured over its velocity limit, or where the joint state is
    /// older than the horizon (no verdict on it may move the arm, and the
    /// scale in force is looked up over a window that assumes so). Every
    /// call is taken as published: its scale governs the arm from now on.
    pub fn decide_moving(
        &mut self,
        shapes: &[WorldShape],
        joints: JointMotionSample,
        now_ns: u64,
    ) -> Result<Decision, GuardError> {
        let mut decision = self.decide(shapes, now_ns)?;
        let stop_distance = self.config.stop_distance;
        let timing = self.timing();
        let Some(control) = self.speed.as_mut() else {
            decision.speed =
                SpeedScale::binary(decision.verdict == GuardVerdict::Clear, stop_distance);
            return Ok(decision);
        };
        let age = joints.age_ns as f64 * 1e-9;
        let in_force = control.governor.in_force(now_ns);
        let speeds = control.monitor.current_speeds(joints.velocities, in_force);
        let clear = decision.verdict == GuardVerdict::Clear;
        let now = |speeds| MotionNow {
            speeds,
            joint_state_age: age,
        };
        let target = match (&speeds, &decision.report) {
            // Another verdict already stops the arm and says why.
            _ if !clear => SpeedScale::binary(false, stop_distance),
            _ if age > timing.horizon => {
                decision.stop(format!(
                    "joint state {age:.3} s old, beyond the horizon {:.3} s: no verdict on it may move the arm",
                    timing.horizon
                ));
                SpeedScale::binary(false, stop_distance)
            }
            (Err(over), _) => {
                let name = control.monitor.joint_name(over.joint);
                decision.stop(format!(
                    "joint {name} moves at {:.3}, over its velocity limit {:.3}",
                    over.speed, over.limit
                ));
                SpeedScale::binary(false, stop_distance)
            }
            (Ok(speeds), Some(report)) => {
                control
                    .monitor
                    .scale(&report.links, stop_distance, &now(speeds), &timing)
            }
            (Ok(_), None) => SpeedScale::binary(false, stop_distance),
        };
        let scale = control.governor.publish(target.scale, now_ns);
        decision.speed = match (&speeds, &decision.report) {
            // Held below the target by the rise limit: what the published
            // scale needs (it is feasible, S_p growing with the scale), and
            // no link limits it.
            (Ok(speeds), Some(report)) if scale < target.scale => SpeedScale {
                scale,
                limiting_link: None,
                protective_distance: control.monitor.needed_at(
                    &report.links,
                    stop_distance,
                    &now(speeds),
                    &timing,
                    scale,
                ),
            },
            _ => SpeedScale { scale, ..target },
        };
        if decision.verdict == GuardVerdict::Clear && scale == 0.0 && target.scale > 0.0 {
            decision.stop(format!(
                "the speed scale rises at most {}/s from a stop",
                control.monitor.motion().scale_rise_per_second
            ));
        } else if decision.verdict == GuardVerdict::Clear && scale == 0.0 {
            let link = target.limiting_link.and_then(|i| self.links.get(i));
            let clearance = decision
                .report
                .as_ref()
                .and_then(|r| target.limiting_link.and_then(|l| r.links.get(l)))
                .copied()
                .unwrap_or(0.0);
            decision.stop(format!(
                "link {} at {clearance:.3} m is within its protective separation distance {:.3} m (reaction, braking and the obstacle's approach meanwhile)",
                link.map_or("?", String::as_str),
                target.protective_distance
            ));
        }
        Ok(decision)
    }
}
