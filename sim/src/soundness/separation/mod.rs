//! A brute-force check of the guard's speed and separation monitoring
//! (ISO/TS 15066, 5.5.4): closed-loop simulations in which a simulated arm
//! runs a random trajectory at the speed scale its verdicts allow, among
//! solids and a walking person moving at up to the obstacle speed bound, and
//! the true separation is checked against the guard's stop distance `C` at
//! every step.
//!
//! Per trajectory (its own seed, replayable with [`run_trajectory`]):
//! - [`SeparationScene`]: solids crossing the arm's workspace at up to the
//!   obstacle speed, in some scenes a person (a vertical capsule) walking
//!   straight across at exactly that speed, and 1–2 sensors rescanning at a
//!   fixed rate, each scan fitted by shroud's fitter and accepted by the
//!   guard when it arrives (scan time + pipeline delay + transit);
//! - an arm (the demo or the URDF arm of [`super::arms`], mounted higher)
//!   with an `ArmMotion` drawn at random, a random trajectory
//!   ([`reference::Reference`]) whose nominal speeds respect its limits, and
//!   joint states at 50 Hz answered by `CollisionGuard::decide_moving` after
//!   a random guard delay;
//! - the simulated arm ([`joints`]) keeps the contract and no better: joint
//!   speeds at most the scale in force times the limit, each verdict applied
//!   by its deadman (`shroud_guard::Deadman`) after a transport delay and
//!   obeyed after a controller lag, the two together at most `T_r`, halted
//!   when its deadman's deadline passes, slowing and braking exactly as its
//!   stopping model's worst case;
//! - the truth ([`distance`]): at every step (2 ms, and at every event) the
//!   exact distance from every arm shape, at the true joint values, to every
//!   solid and the floor at that instant; between steps a Lipschitz bound
//!   (the arm's and the obstacles' speed bounds) and bisection close the gap,
//!   so that no dip between samples goes unseen.
//!
//! A *failure* is an instant at which the arm is moving and some shape is
//! nearer to a solid or the floor than `C` less the scene's sampling margin
//! (the largest gap between neighbouring rays of its sensors, as in
//! [`super::run`]). The same trajectories run a second time under a binary
//! guard at the same safety (a verdict moves the arm only when the full-speed
//! bound holds) for the productivity figures.

mod closed_loop;
pub mod distance;
pub mod joints;
pub mod reference;
mod report;
mod scene;

pub use closed_loop::{run, run_trajectory};
pub use joints::ArmBehaviour;
pub use report::{Failure, Mode, ModeStats, Productivity, SeparationReport};
pub use scene::{LoopTiming, ScanningSensor, SeparationArms, SeparationScene, StateTiming};

use super::SoundnessError;

/// What a separation run draws and how the guard and the arm are set up.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeparationParams {
    /// `C`: the guard's stop distance (m).
    pub stop_distance: f64,
    /// Bound on every solid's speed (the person walks at exactly this), and
    /// the guard's `max_obstacle_speed` (m/s).
    pub obstacle_speed: f64,
    /// The guard's horizon `H` (s); the arm's deadman deadline is at most it.
    pub horizon: f64,
    /// The guard's max age (s).
    pub max_age: f64,
    /// Simulated seconds per trajectory.
    pub duration: f64,
    /// Joint states per second.
    pub joint_rate: f64,
    /// Scan rates of the sensors are drawn in `[min, max]` (Hz).
    pub scan_rate_min: f64,
    pub scan_rate_max: f64,
    /// Most rays one scan casts.
    pub max_rays: usize,
    /// The arm's integration and truth step (s); events split it further.
    pub step: f64,
    /// Share of scenes with a person walking across.
    pub person_share: f64,
    /// Sensors cast parallel rays along their look (the sensor the guard's
    /// views assume); off: perspective sensors whose clouds state their
    /// field of view and their rays without a return.
    pub parallel_rays: bool,
    /// Share of views fitted as sandwiches (else upper only).
    pub sandwich_share: f64,
    /// Share of joint states that carry measured velocities.
    pub velocities_share: f64,
    /// How much higher than in [`super::arms`] the arms are mounted (m).
    pub mount_lift: f64,
    /// Every shape of every waypoint is at least this high above the floor.
    pub min_height: f64,
    /// The fixed task of the productivity figures: this many seconds of the
    /// trajectory at nominal speed.
    pub task: f64,
    /// How the arm treats its verdicts (the contract, or a negative control).
    pub behaviour: ArmBehaviour,
    /// Negative control: the obstacle speed the guard is told, when it is
    /// not `obstacle_speed` (a guard that underestimates it is unsound).
    pub declared_obstacle_speed: Option<f64>,
    /// Also run every trajectory under the binary guard.
    pub compare_binary: bool,
}

impl Default for SeparationParams {
    fn default() -> Self {
        Self {
            stop_distance: 0.1,
            obstacle_speed: 1.6,
            horizon: 0.1,
            max_age: 0.5,
            duration: 3.0,
            joint_rate: 50.0,
            scan_rate_min: 10.0,
            scan_rate_max: 15.0,
            max_rays: 12_000,
            step: 0.002,
            person_share: 0.5,
            parallel_rays: true,
            sandwich_share: 0.0,
            velocities_share: 0.75,
            mount_lift: 0.8,
            min_height: 1.0,
            task: 1.0,
            behaviour: ArmBehaviour::Obeys,
            declared_obstacle_speed: None,
            compare_binary: true,
        }
    }
}

impl SeparationParams {
    pub fn validate(&self) -> Result<(), SoundnessError> {
        let bad = |parameter, reason, value| {
            Err(SoundnessError::BadParameter {
                parameter,
                reason,
                value,
            })
        };
        let positive = |x: f64| x.is_finite() && x > 0.0;
        let share = |x: f64| (0.0..=1.0).contains(&x);
        if !positive(self.stop_distance) {
            return bad(
                "stop_distance",
                "must be finite and > 0",
                self.stop_distance,
            );
        }
        if !(self.obstacle_speed.is_finite() && self.obstacle_speed >= 0.0) {
            return bad(
                "obstacle_speed",
                "must be finite and >= 0",
                self.obstacle_speed,
            );
        }
        if !(positive(self.horizon) && self.horizon <= shroud_guard::MAX_HORIZON) {
            return bad("horizon", "must lie in (0, 1] s", self.horizon);
        }
        if !(positive(self.max_age) && self.max_age <= 10.0) {
            return bad("max_age", "must lie in (0, 10] s", self.max_age);
        }
        if !(positive(self.duration) && self.duration <= 60.0) {
            return bad("duration", "must lie in (0, 60] s", self.duration);
        }
        if !(positive(self.joint_rate) && self.joint_rate <= 1000.0) {
            return bad("joint_rate", "must lie in (0, 1000] Hz", self.joint_rate);
        }
        if !(positive(self.scan_rate_min)
            && self.scan_rate_max >= self.scan_rate_min
            && self.scan_rate_max <= 100.0)
        {
            return bad(
                "scan_rate_max",
                "must lie in [scan_rate_min, 100] Hz with scan_rate_min > 0",
                self.scan_rate_max,
            );
        }
        if !(100..=1_000_000).contains(&self.max_rays) {
            return bad("max_rays", "must lie in [100, 1e6]", self.max_rays as f64);
        }
        if !(positive(self.step) && self.step <= 0.01) {
            return bad("step", "must lie in (0, 0.01] s", self.step);
        }
        for (parameter, value) in [
            ("person_share", self.person_share),
            ("sandwich_share", self.sandwich_share),
            ("velocities_share", self.velocities_share),
        ] {
            if !share(value) {
                return bad(parameter, "must lie in [0, 1]", value);
            }
        }
        if !(self.mount_lift.is_finite() && (0.0..=2.0).contains(&self.mount_lift)) {
            return bad("mount_lift", "must lie in [0, 2] m", self.mount_lift);
        }
        if !(self.min_height.is_finite() && self.min_height >= 0.0) {
            return bad("min_height", "must be finite and >= 0", self.min_height);
        }
        if !positive(self.task) {
            return bad("task", "must be finite and > 0", self.task);
        }
        if let Some(v) = self.declared_obstacle_speed {
            if !(v.is_finite() && v >= 0.0) {
                return bad("declared_obstacle_speed", "must be finite and >= 0", v);
            }
        }
        match self.behaviour {
            ArmBehaviour::Late(extra) if !(extra.is_finite() && extra >= 0.0) => {
                bad("behaviour", "a late arm's extra delay must be >= 0", extra)
            }
            ArmBehaviour::SoftBrakes(factor) if !(factor.is_finite() && factor >= 1.0) => bad(
                "behaviour",
                "soft brakes' factor must be finite and >= 1",
                factor,
            ),
            _ => Ok(()),
        }
    }
}
