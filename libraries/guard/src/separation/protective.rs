//! The protective separation distance of ISO/TS 15066 (5.5.4),
//! `S_p = S_h + S_r + S_s + C + Z_d + Z_r`, for one link at one speed scale,
//! with each term bounded for the guard's own timeline (Marvel and Norcross,
//! "Implementing speed and separation monitoring in collaborative robot
//! workcells", 2017, give the constant-speed form).
//!
//! The timeline of a verdict decided at `t_d` on a joint state sampled `age`
//! earlier, in the order the arm lives it (phases summed one after another,
//! which can only lengthen them):
//! 1. from the sample until the verdict takes effect (`age + T_r`), joint `j`
//!    moves at most at its current bound `w_j` (the faster of its measured
//!    speed and the scale in force times its limit);
//! 2. if the new scale is slower, the joint slows to `v_j = scale · limit`,
//!    travelling `(w_j² - v_j²) / 2a` under a constant deceleration, and
//!    less than a full stop from `w_j` by a table (speed falls monotonically
//!    while braking);
//! 3. at most `v_j` until the verdict expires (the horizon `H`);
//! 4. then it stops from at most `v_j`.
//!
//! Phases 2 to 4 are also bounded as a whole by `max(w_j, v_j)` for `H`
//! and a stop from that speed; each joint counts the smaller bound
//! (`after_reaction`), which keeps `S_p` growing with the scale.
//!
//! A stop verdict at any moment is covered too: it stops from `w_j` after
//! phase 1 or from `v_j` later, each counted above. `S_r + S_s` is each
//! joint's travel over these phases times its lever arm on the link, summed
//! over the joints. `S_h` is what the obstacle covers from the end of the
//! guard's motion allowance (`t_d + H`, already subtracted from the
//! clearance) until the arm has stopped: `v_h (T_r + T_slow + T_stop)`, over
//! the joints that move the link (a link no joint moves, the base, cannot
//! get out of the way: it needs the stop distance and `Z_r` alone). `C` is
//! the guard's stop distance; `Z_d` is each view's position error, already
//! subtracted from the clearance; `Z_r` is the arm file's position
//! uncertainty.

use super::lever::LeverArms;
use super::motion::{ArmMotion, JointMotion};
use super::stopping::Stop;

/// What a decision knows of the arm's motion besides the scale it weighs.
#[derive(Debug, Clone, Copy)]
pub struct MotionNow<'a> {
    /// Per actuated joint, the fastest it may be moving until the new verdict
    /// takes effect (rad/s or m/s, `>= 0`).
    pub speeds: &'a [f64],
    /// Seconds from the joint state's sample to the decision (`>= 0`).
    pub joint_state_age: f64,
}

/// The guard-side timing that enters `S_p`.
#[derive(Debug, Clone, Copy)]
pub struct Timing {
    /// `H`: how long after the decision the arm may still move on it.
    pub horizon: f64,
    /// `v_h`: the bound on any obstacle's speed.
    pub obstacle_speed: f64,
}

/// `S_p - C` for one link: how much clearance beyond the stop distance the
/// link needs at a scale, and its parts.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Protective {
    /// `S_r + S_s`: the link's travel until it has stopped.
    pub arm_travel: f64,
    /// `S_h` beyond the motion allowance.
    pub obstacle_travel: f64,
    /// `Z_r`.
    pub uncertainty: f64,
}

impl Protective {
    pub fn total(&self) -> f64 {
        self.arm_travel + self.obstacle_travel + self.uncertainty
    }
}

/// One joint's travel from the moment the new verdict takes effect until it
/// has stopped, and how long its slowing and stopping take beyond the
/// horizon, moving at `w` before and allowed `v` after: the smaller of two
/// bounds that both hold.
/// - In phases: slow from `w` to `v` (if slower), `v` for the horizon, stop
///   from `v` (tight under a constant deceleration).
/// - At most `m = max(w, v)` throughout the horizon (slowing never speeds
///   up), then a stop from at most `m` (tight for a table, whose "slowing"
///   is a whole stop from `w`).
///
/// Both grow with `v` once `v >= w`, and below `w` the second does not
/// depend on `v` while the first grows with it: the smaller one, and so
/// `S_p`, never shrinks as the scale grows, so any scale below a feasible one
/// is feasible too (the rise limit relies on it).
fn after_reaction(joint: &JointMotion, w: f64, v: f64, horizon: f64) -> (f64, f64) {
    let limit = joint.max_velocity;
    let slowing = if w > v {
        joint.stopping.slow(w, v, limit)
    } else {
        Stop::default()
    };
    let stop = joint.stopping.stop(v, limit);
    let phased = (
        slowing.distance + v * horizon + stop.distance,
        slowing.time + stop.time,
    );
    let m = w.max(v);
    let full = joint.stopping.stop(m, limit);
    let steady = (m * horizon + full.distance, full.time);
    (phased.0.min(steady.0), phased.1.min(steady.1))
}

/// `S_p - C` of link `link` at `scale` (in [0, 1]).
pub fn protective(
    motion: &ArmMotion,
    levers: &LeverArms,
    link: usize,
    now: &MotionNow,
    timing: &Timing,
    scale: f64,
) -> Protective {
    let reaction = now.joint_state_age + motion.reaction_time;
    let mut arm_travel = 0.0;
    let mut stop_time = 0.0f64;
    let mut moves = false;
    for ((joint, &lever), &w) in motion
        .joints
        .iter()
        .zip(levers.of_link(link))
        .zip(now.speeds)
    {
        // Joints after the link do not move it: neither their travel nor
        // their stop counts.
        if lever == 0.0 {
            continue;
        }
        moves = true;
        let (rest, time) = after_reaction(joint, w, scale * joint.max_velocity, timing.horizon);
        arm_travel += lever * (w * reaction + rest);
        stop_time = stop_time.max(time);
    }
    // A link no joint moves (the base) cannot get out of the way by
    // stopping: it keeps the stop distance (and Z_r) alone, as without
    // monitoring.
    let obstacle_travel = if moves {
        timing.obstacle_speed * (motion.reaction_time + stop_time)
    } else {
        0.0
    };
    Protective {
        arm_travel,
        obstacle_travel,
        uncertainty: motion.position_uncertainty,
    }
}
