//! The closed loop of one trajectory: scans fitted and accepted by a real
//! `CollisionGuard` with a `SpeedMonitor`, joint states decided by
//! `decide_moving`, verdicts taken by a real `Deadman`, the simulated arm
//! obeying them, and the truth checked all along.
//!
//! Time is one axis in integer nanoseconds from the scene's start (the
//! guard's monotonic clock and the arm's read that plus a constant, the
//! guard's wall clock a constant more). The loop advances from event to
//! event (a view's arrival, a joint state, a decision, a verdict reaching
//! the deadman, a change of what the deadman lets the motion do) and at
//! least every `step`; between two of them the scale the arm obeys is
//! constant, so every sub-step is integrated exactly ([`super::joints`]).

use super::super::run::scene_seed;
use super::super::solids::Solid;
use super::super::truth::Core;
use super::super::SoundnessError;
use super::distance::{nearest_at, Nearest};
use super::joints::{ArmBehaviour, Joint, Segment};
use super::report::{Failure, Mode, ModeStats, SeparationReport};
use super::scene::{SeparationArms, SeparationScene};
use super::SeparationParams;
use rayon::prelude::*;
use shroud_guard::{
    ArmModel, ArmPose, CollisionGuard, Deadman, Envelope, GuardConfig, GuardPolicy,
    JointMotionSample, Motion, SpeedMonitor, StoppingModel, SurrogateInput, UnobservedPolicy,
};
use shroud_msg::GuardVerdict;
use shroud_surrogate::{fit_surrogate, FitOptions};
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// The clocks at scene time 0 (ns): the guard's and the arm's monotonic
/// clocks, and the guard's wall clock `WALL_OFFSET_NS` ahead.
const MONO_AT_ZERO_NS: u64 = 1_000_000_000;
const WALL_OFFSET_NS: u64 = 1_750_000_000_000_000_000;

/// Fewest points a scan needs to be fitted (as in the soundness harness).
const MIN_POINTS: usize = 50;

/// The controller's pull back to its reference (1/s), on top of the
/// reference's own velocity: after a stop off the path, the arm rejoins it.
const TRACKING_GAIN: f64 = 10.0;

/// Halvings of a sub-step before a Lipschitz bound under the threshold that
/// no sample confirms is counted as a failure anyway (2 ms / 2^24 is about
/// 0.1 ns).
const MAX_BISECTIONS: u32 = 24;

fn mono(t_ns: u64) -> u64 {
    MONO_AT_ZERO_NS + t_ns
}

fn wall(t_ns: u64) -> u64 {
    mono(t_ns) + WALL_OFFSET_NS
}

fn ns(seconds: f64) -> u64 {
    (seconds.max(0.0) * 1e9).round() as u64
}

fn secs(t_ns: u64) -> f64 {
    t_ns as f64 * 1e-9
}

/// Runs `trajectories` trajectories (in parallel) and adds up their
/// reports. Trajectory `i` has the seed `scene_seed(seed, i)`.
pub fn run(
    params: &SeparationParams,
    trajectories: u64,
    seed: u64,
) -> Result<SeparationReport, SoundnessError> {
    params.validate()?;
    let arms = SeparationArms::load(params.mount_lift)?;
    (0..trajectories)
        .into_par_iter()
        .map(|i| run_trajectory(&arms, params, scene_seed(seed, i), i))
        .try_reduce(SeparationReport::empty, |a, b| Ok(a.merged(b)))
}

/// One scan as the guard receives it.
struct ScanView {
    view: usize,
    arrival_ns: u64,
    input: SurrogateInput,
}

/// Every scan of every sensor, fitted as the fit node does (and as the
/// soundness harness's `views_of`), in the order they reach the guard; and
/// the counts for the report. The scene's sampling margin is the largest of
/// the sensors that gave a view.
fn scans_of(scene: &SeparationScene, params: &SeparationParams) -> (Vec<ScanView>, ScanCounts) {
    let mut views = Vec::new();
    let mut counts = ScanCounts::default();
    for (view, setup) in scene.sensors.iter().enumerate() {
        for (k, &(pipeline, transit)) in setup.delays.iter().enumerate() {
            let time = setup.scan_time(k);
            if time > params.duration {
                break;
            }
            let mut sensor = setup.sensor;
            sensor.time = time;
            let scan = sensor.scan(&scene.solids);
            counts.scans += 1;
            counts.points += scan.points.len() as u64;
            let envelope = (scan.points.len() >= MIN_POINTS)
                .then(|| {
                    let options = FitOptions {
                        cols: setup.cols,
                        rows: setup.rows,
                        direction: sensor.look.to_array(),
                        sides: setup.sides,
                        ..FitOptions::default()
                    };
                    let surrogate = fit_surrogate(&scan.points, &options).ok()?;
                    let no_return = sensor.stated_no_return(&scan);
                    Envelope::new(&surrogate)
                        .ok()?
                        .with_field_of_view(sensor.stated_field_of_view())
                        .ok()?
                        .with_no_return(no_return.as_ref())
                        .ok()
                })
                .flatten();
            let Some(envelope) = envelope else {
                continue;
            };
            counts.views += 1;
            counts.margin = counts.margin.max(sensor.sampling_margin());
            views.push(ScanView {
                view,
                arrival_ns: ns(time + pipeline + transit),
                input: SurrogateInput {
                    envelope,
                    stamp_ns: wall(ns(time)),
                    sequence: k as u64,
                    pipeline_ns: ns(pipeline),
                    published_ns: wall(ns(time + pipeline)),
                    position_error: 0.0,
                },
            });
        }
    }
    views.sort_by_key(|v| v.arrival_ns);
    (views, counts)
}

#[derive(Debug, Default)]
struct ScanCounts {
    scans: u64,
    views: u64,
    points: u64,
    margin: f64,
}

/// One trajectory (its scene drawn from `seed`) under the scaled guard and,
/// if asked, the binary one: the report of this trajectory alone. `index`
/// is its place in the run (for the report of a failure).
pub fn run_trajectory(
    arms: &SeparationArms,
    params: &SeparationParams,
    seed: u64,
    index: u64,
) -> Result<SeparationReport, SoundnessError> {
    let scene = SeparationScene::draw(arms, params, seed);
    let (views, counts) = scans_of(&scene, params);
    let mut report = SeparationReport::empty();
    report.trajectories = 1;
    report.crossings = u64::from(scene.person.is_some());
    report.scans = counts.scans;
    report.views = counts.views;
    report.points = counts.points;
    report.max_margin = counts.margin;
    let threshold = params.stop_distance - counts.margin;
    report.min_threshold = threshold;
    let modes: &[Mode] = if params.compare_binary {
        &[Mode::Scaled, Mode::Binary]
    } else {
        &[Mode::Scaled]
    };
    let mut failed = false;
    for &mode in modes {
        let out = Sim::new(arms, params, &scene, &views, mode, threshold)?.run()?;
        failed |= out.failures > 0;
        report.refinements += out.refinements;
        report.substeps += out.substeps;
        report.min_separation = report.min_separation.min(out.min_any);
        let mut stats = out.stats;
        stats.trajectories = 1;
        let first = out.first_failure.map(|mut f| {
            f.index = index;
            f
        });
        report.first_failure = match (report.first_failure.take(), first) {
            (Some(a), _) => Some(a),
            (None, b) => b,
        };
        let productivity = match mode {
            Mode::Scaled => {
                report.verdicts = out.counts;
                report.full_speed = out.full_speed;
                report.scaled = out.scaled;
                report.smallest_scale = out.smallest_scale;
                report.failures = out.failures;
                report.min_separation_moving = out.min_moving;
                report.closest = out.closest.map(|mut c| {
                    c.index = index;
                    c
                });
                &mut report.scaled_mode
            }
            Mode::Binary => {
                report.binary_clear = out.full_speed;
                report.binary_stop = out.counts.total() - out.full_speed;
                report.binary_failures = out.failures;
                report.binary_min_separation_moving = out.min_moving;
                &mut report.binary_mode
            }
        };
        productivity.all = stats;
        if scene.person.is_some() {
            productivity.crossing = stats;
        }
    }
    report.failing_trajectories = u64::from(failed);
    Ok(report)
}

/// What one guard's run of a trajectory gave.
#[derive(Debug, Default)]
struct Outcome {
    stats: ModeStats,
    counts: super::super::report::VerdictCounts,
    /// Clear verdicts (as the arm took them) at scale 1 and in (0, 1).
    full_speed: u64,
    scaled: u64,
    smallest_scale: f64,
    failures: u64,
    first_failure: Option<Failure>,
    min_moving: f64,
    closest: Option<Failure>,
    min_any: f64,
    refinements: u64,
    substeps: u64,
}

/// A joint state as sent.
#[derive(Debug, Clone)]
struct Sample {
    at_ns: u64,
    reported: Vec<f64>,
    velocities: Vec<f64>,
}

/// Events at one time are handled in this order.
const VIEW: u8 = 0;
const JOINT_STATE: u8 = 1;
const DECISION: u8 = 2;
const VERDICT: u8 = 3;
const BOUNDARY: u8 = 4;

struct Sim<'a> {
    params: &'a SeparationParams,
    scene: &'a SeparationScene,
    views: &'a [ScanView],
    arm: &'a ArmModel,
    mode: Mode,
    guard: CollisionGuard,
    deadman: Deadman,
    /// What the deadman lets the arm do, from each verdict's arrival on:
    /// `(from, scale, until)`: the scale until `until`, 0 after it.
    timeline: Vec<(u64, f64, u64)>,
    cursor: usize,
    /// The controller's lag (plus a late arm's extra delay).
    lag_ns: u64,
    joints: Vec<Joint>,
    models: Vec<StoppingModel>,
    limits: Vec<f64>,
    soften: f64,
    /// Nominal time along the trajectory.
    tau: f64,
    samples: Vec<Option<Sample>>,
    answers: Vec<Option<(GuardVerdict, f64)>>,
    last_decision_ns: u64,
    events: BinaryHeap<Reverse<(u64, u8, usize)>>,
    truth: Truth<'a>,
    out: Outcome,
    reference_q: Vec<f64>,
    reference_dq: Vec<f64>,
}

impl<'a> Sim<'a> {
    fn new(
        arms: &'a SeparationArms,
        params: &'a SeparationParams,
        scene: &'a SeparationScene,
        views: &'a [ScanView],
        mode: Mode,
        threshold: f64,
    ) -> Result<Self, SoundnessError> {
        let arm = arms.get(scene.arm);
        let mut motion = scene.motion.clone();
        if mode == Mode::Binary {
            // A binary guard has no use for a slow rise: it moves at full
            // speed or not at all.
            motion.scale_rise_per_second = 1e9;
        }
        let config = GuardConfig {
            stop_distance: params.stop_distance,
            max_report: 2.0 * params.stop_distance,
            refine_depth: 3,
            max_obstacle_speed: params
                .declared_obstacle_speed
                .unwrap_or(params.obstacle_speed),
            horizon: params.horizon,
        };
        let policy = GuardPolicy {
            max_age_ns: ns(params.max_age),
            unobserved: UnobservedPolicy::Stop,
            ..GuardPolicy::default()
        };
        let names = (0..scene.sensors.len())
            .map(|k| format!("sensor{k}"))
            .collect();
        let links = arm.links().iter().map(|l| l.name.clone()).collect();
        let guard = CollisionGuard::new(names, links, policy, config)?
            .with_speed_monitor(SpeedMonitor::new(arm, motion)?);
        let timing = &scene.timing;
        let extra = match params.behaviour {
            ArmBehaviour::Late(extra) => extra,
            _ => 0.0,
        };
        let soften = match params.behaviour {
            ArmBehaviour::SoftBrakes(factor) => factor,
            _ => 1.0,
        };
        let start = scene.reference.start().to_vec();
        let dof = start.len();
        let mut events = BinaryHeap::new();
        for (i, v) in views.iter().enumerate() {
            events.push(Reverse((v.arrival_ns, VIEW, i)));
        }
        for k in 0..timing.states.len() {
            events.push(Reverse((ns(timing.sample_time(k)), JOINT_STATE, k)));
        }
        let truth = Truth::new(
            arm,
            &scene.solids,
            threshold,
            arms.reach(scene.arm),
            params,
            scene,
            mode,
        );
        Ok(Self {
            params,
            scene,
            views,
            arm,
            mode,
            guard,
            deadman: Deadman::new(ns(timing.deadline)),
            timeline: Vec::new(),
            cursor: 0,
            lag_ns: ns(timing.controller_lag + extra),
            joints: start.iter().map(|&q| Joint::at_rest(q)).collect(),
            models: scene
                .motion
                .joints
                .iter()
                .map(|j| j.stopping.clone())
                .collect(),
            limits: scene.motion.joints.iter().map(|j| j.max_velocity).collect(),
            soften,
            tau: 0.0,
            samples: vec![None; timing.states.len()],
            answers: vec![None; timing.states.len()],
            last_decision_ns: 0,
            events,
            truth,
            out: Outcome {
                smallest_scale: f64::INFINITY,
                min_moving: f64::INFINITY,
                min_any: f64::INFINITY,
                ..Outcome::default()
            },
            reference_q: vec![0.0; dof],
            reference_dq: vec![0.0; dof],
        })
    }

    fn run(mut self) -> Result<Outcome, SoundnessError> {
        let end = ns(self.params.duration);
        let step = ns(self.params.step).max(1);
        let q: Vec<f64> = self.joints.iter().map(|j| j.q).collect();
        self.truth.start(&q, 0.0)?;
        let (mut now, mut grid) = (0u64, step);
        loop {
            let next = self
                .events
                .peek()
                .map_or(u64::MAX, |e| e.0 .0)
                .min(grid)
                .min(end);
            if next > now {
                self.integrate(now, next)?;
                now = next;
            }
            while let Some(&Reverse((t, kind, i))) = self.events.peek() {
                if t != now {
                    break;
                }
                self.events.pop();
                self.handle(kind, i, now)?;
            }
            while grid <= now {
                grid += step;
            }
            if now >= end {
                break;
            }
        }
        self.out.stats.seconds = secs(end);
        self.out.stats.progress = self.tau;
        self.truth.finish(&mut self.out);
        Ok(self.out)
    }

    /// The scale the deadman lets the arm run at, as of deadman time `y`.
    fn command_at(&mut self, y: u64) -> f64 {
        while self.cursor + 1 < self.timeline.len() && self.timeline[self.cursor + 1].0 <= y {
            self.cursor += 1;
        }
        match self.timeline.get(self.cursor) {
            Some(&(from, scale, until)) if from <= y && y <= until => scale,
            _ => 0.0,
        }
    }

    fn integrate(&mut self, t0: u64, t1: u64) -> Result<(), SoundnessError> {
        let mid = t0 + (t1 - t0) / 2;
        let scale = match mid.checked_sub(self.lag_ns) {
            Some(y) => self.command_at(y),
            None => 0.0,
        };
        let (cap, pace) = match self.params.behaviour {
            ArmBehaviour::IgnoresScale if scale > 0.0 => (1.0, 1.0),
            _ => (scale, scale),
        };
        let (s0, s1) = (secs(t0), secs(t1));
        let h = s1 - s0;
        self.scene
            .reference
            .at(self.tau, &mut self.reference_q, &mut self.reference_dq);
        let segments: Vec<Segment> = (0..self.joints.len())
            .map(|j| {
                let joint = &mut self.joints[j];
                let desired =
                    pace * self.reference_dq[j] + TRACKING_GAIN * (self.reference_q[j] - joint.q);
                joint.plan(
                    s0,
                    cap * self.limits[j],
                    desired,
                    &self.models[j],
                    self.limits[j],
                    self.soften,
                )
            })
            .collect();
        self.truth.interval(s0, s1, &segments, scale)?;
        for (joint, segment) in self.joints.iter_mut().zip(&segments) {
            joint.finish(segment, s1);
        }
        self.tau += pace * h;
        let stats = &mut self.out.stats;
        stats.scale_seconds += cap * h;
        if segments.iter().any(|s| s.max_speed() > 0.0) {
            stats.moving_seconds += h;
        }
        if stats.tasks_done == 0 && self.tau >= self.params.task {
            stats.tasks_done = 1;
            stats.task_seconds = s1;
        }
        self.out.substeps += 1;
        Ok(())
    }

    fn handle(&mut self, kind: u8, i: usize, now: u64) -> Result<(), SoundnessError> {
        match kind {
            VIEW => {
                let v = &self.views[i];
                // On one clock axis nothing is refused; a refusal would only
                // leave the view out, which the truth still judges.
                let _ = self
                    .guard
                    .accept(v.view, v.input.clone(), mono(now), wall(now));
            }
            JOINT_STATE => {
                let timing = &self.scene.timing.states[i];
                let reported = self
                    .joints
                    .iter()
                    .zip(&timing.noise)
                    .map(|(j, n)| j.q + n)
                    .collect();
                let velocities = self.joints.iter().map(|j| j.v).collect();
                self.deadman.sent(i as u64, mono(now), mono(now));
                self.samples[i] = Some(Sample {
                    at_ns: now,
                    reported,
                    velocities,
                });
                let decide = (now + ns(timing.guard_delay)).max(self.last_decision_ns);
                self.last_decision_ns = decide;
                self.events.push(Reverse((decide, DECISION, i)));
            }
            DECISION => {
                let Some(sample) = self.samples[i].take() else {
                    return Ok(());
                };
                let timing = &self.scene.timing.states[i];
                let pose = self.arm.forward(&sample.reported)?;
                let joints = JointMotionSample {
                    velocities: timing.velocities.then_some(sample.velocities.as_slice()),
                    age_ns: now - sample.at_ns,
                };
                let decision = self.guard.decide_moving(&pose.shapes, joints, mono(now))?;
                self.out.counts.count(decision.verdict);
                let clear = decision.verdict == GuardVerdict::Clear;
                let scale = decision.speed.scale;
                let answer = match self.mode {
                    Mode::Scaled => (decision.verdict, scale),
                    Mode::Binary if clear && scale >= 1.0 => (GuardVerdict::Clear, 1.0),
                    Mode::Binary => (GuardVerdict::Stop, 0.0),
                };
                if answer.0 == GuardVerdict::Clear {
                    if answer.1 >= 1.0 {
                        self.out.full_speed += 1;
                    } else {
                        self.out.scaled += 1;
                        self.out.smallest_scale = self.out.smallest_scale.min(answer.1);
                    }
                }
                self.answers[i] = Some(answer);
                // The stamp travels with the sample: the deadman matches it.
                self.samples[i] = Some(sample);
                let slows =
                    answer.0 != GuardVerdict::Clear || answer.1 < self.deadman.scale(mono(now));
                let lost = timing.dropped || (self.scene.timing.slowing_lost && slows);
                if !lost {
                    self.events
                        .push(Reverse((now + ns(timing.transport), VERDICT, i)));
                }
            }
            VERDICT => {
                let (Some((verdict, scale)), Some(sample)) = (self.answers[i], &self.samples[i])
                else {
                    return Ok(());
                };
                let stamp = mono(sample.at_ns);
                self.deadman.scaled_verdict(i as u64, stamp, verdict, scale);
                let moving = self.deadman.motion(mono(now)) == Motion::Move;
                let scale = if moving {
                    self.deadman.scale(mono(now))
                } else {
                    0.0
                };
                // The last instant the deadman still lets the arm move
                // without another verdict (binary search: it only halts).
                let until = if moving {
                    let (mut lo, mut hi) = (now, now + self.deadman.deadline_ns() + 1);
                    while hi - lo > 1 {
                        let m = lo + (hi - lo) / 2;
                        if self.deadman.motion(mono(m)) == Motion::Move {
                            lo = m;
                        } else {
                            hi = m;
                        }
                    }
                    lo
                } else {
                    now
                };
                self.timeline.push((now, scale, until));
                self.events.push(Reverse((now + self.lag_ns, BOUNDARY, 0)));
                self.events
                    .push(Reverse((until + self.lag_ns, BOUNDARY, 0)));
            }
            _ => {}
        }
        Ok(())
    }
}

/// One shape over one sub-step, searched for a dip under the threshold:
/// the joints' motion, the Lipschitz bound and the scale the arm obeys.
struct Dip<'s> {
    segments: &'s [Segment],
    shape: usize,
    lipschitz: f64,
    scale: f64,
}

/// The truth along one run: exact distances at every sub-step's end, the
/// Lipschitz bound in between, failures and the smallest separations.
struct Truth<'a> {
    arm: &'a ArmModel,
    solids: &'a [Solid],
    scene: &'a SeparationScene,
    mode: Mode,
    threshold: f64,
    /// Distances beyond this may be lower bounds.
    cutoff: f64,
    /// [`SeparationArms::reach`].
    reach: f64,
    /// The fastest solid's speed.
    obstacle_speed: f64,
    pose: ArmPose,
    /// Per shape, its distance and what to at the last sub-step's end.
    last: Vec<(f64, Nearest)>,
    next: Vec<(f64, Nearest)>,
    q: Vec<f64>,
    failures: u64,
    first: Option<Failure>,
    min_moving: f64,
    /// The moment of `min_moving`.
    closest: Option<Failure>,
    min_any: f64,
    refinements: u64,
}

impl<'a> Truth<'a> {
    fn new(
        arm: &'a ArmModel,
        solids: &'a [Solid],
        threshold: f64,
        reach: f64,
        params: &SeparationParams,
        scene: &'a SeparationScene,
        mode: Mode,
    ) -> Self {
        Self {
            arm,
            solids,
            scene,
            mode,
            threshold,
            cutoff: (2.0 * params.stop_distance).max(1.0),
            reach,
            obstacle_speed: solids
                .iter()
                .map(|s| s.velocity.length())
                .fold(0.0, f64::max),
            pose: ArmPose::default(),
            last: Vec::new(),
            next: Vec::new(),
            q: Vec::new(),
            failures: 0,
            first: None,
            min_moving: f64::INFINITY,
            closest: None,
            min_any: f64::INFINITY,
            refinements: 0,
        }
    }

    /// Distances of every shape at joint values `q`, time `t`, into `out`.
    fn distances(&mut self, q: &[f64], t: f64, out_next: bool) -> Result<(), SoundnessError> {
        self.arm.forward_into(q, &mut self.pose)?;
        let out = if out_next {
            &mut self.next
        } else {
            &mut self.last
        };
        out.clear();
        for shape in &self.pose.shapes {
            out.push(nearest_at(&Core::of(shape), self.solids, t, self.cutoff));
        }
        Ok(())
    }

    /// One shape's distance at time `x` of the sub-step `segments`.
    fn shape_at(
        &mut self,
        segments: &[Segment],
        shape: usize,
        x: f64,
    ) -> Result<(f64, Nearest), SoundnessError> {
        self.q.clear();
        self.q.extend(segments.iter().map(|s| s.position(x)));
        self.arm.forward_into(&self.q, &mut self.pose)?;
        let core = Core::of(&self.pose.shapes[shape]);
        Ok(nearest_at(&core, self.solids, x, self.cutoff))
    }

    fn start(&mut self, q: &[f64], t: f64) -> Result<(), SoundnessError> {
        self.distances(q, t, false)?;
        self.min_any = self.last.iter().map(|d| d.0).fold(self.min_any, f64::min);
        Ok(())
    }

    /// The record of shape `shape` at `time` (its link and obstacle named).
    fn moment(
        &self,
        shape: usize,
        time: f64,
        distance: f64,
        what: Nearest,
        unresolved: bool,
        scale: f64,
    ) -> Failure {
        let link = self
            .pose
            .shapes
            .get(shape)
            .and_then(|s| self.arm.links().get(s.link))
            .map_or("?".to_string(), |l| l.name.clone());
        let obstacle = match what {
            Nearest::Floor => "the floor".to_string(),
            Nearest::Solid(k) if self.scene.person == Some(k) => format!("the person (solid {k})"),
            Nearest::Solid(k) => format!("solid {k}"),
        };
        Failure {
            index: 0,
            seed: self.scene.seed,
            mode: self.mode,
            arm: self.scene.arm,
            time,
            link,
            shape,
            distance,
            threshold: self.threshold,
            obstacle,
            unresolved,
            scale,
        }
    }

    /// The moving arm's shape `shape` is `distance` from `what` at `time`.
    fn moving(&mut self, shape: usize, time: f64, distance: f64, what: Nearest, scale: f64) {
        if distance < self.min_moving {
            self.min_moving = distance;
            self.closest = Some(self.moment(shape, time, distance, what, false, scale));
        }
    }

    fn fail(
        &mut self,
        shape: usize,
        time: f64,
        distance: f64,
        what: Nearest,
        unresolved: bool,
        scale: f64,
    ) {
        if self.first.as_ref().is_none_or(|f| time < f.time) {
            self.first = Some(self.moment(shape, time, distance, what, unresolved, scale));
        }
    }

    /// The sub-step from `t0` to `t1`: exact distances at `t1`; a failure
    /// where the arm moves and a distance is under the threshold at either
    /// end or, by bisection, in between, wherever the Lipschitz bound
    /// (`reach` times the joints' speeds plus the fastest solid's speed)
    /// allows a dip under it.
    fn interval(
        &mut self,
        t0: f64,
        t1: f64,
        segments: &[Segment],
        scale: f64,
    ) -> Result<(), SoundnessError> {
        let q: Vec<f64> = segments.iter().map(|s| s.position(t1)).collect();
        self.distances(&q, t1, true)?;
        let moving_start = segments.iter().any(|s| s.max_speed() > 0.0);
        let moving_end = segments.iter().any(|s| s.speed(t1) > 0.0);
        let mut failed = false;
        let smallest = |d: &[(f64, Nearest)]| {
            d.iter()
                .enumerate()
                .min_by(|a, b| a.1 .0.total_cmp(&b.1 .0))
                .map(|(i, &(d, w))| (i, d, w))
        };
        if let Some((shape, d, what)) = smallest(&self.next) {
            self.min_any = self.min_any.min(d);
            if moving_end {
                self.moving(shape, t1, d, what, scale);
                if d < self.threshold {
                    self.fail(shape, t1, d, what, false, scale);
                    failed = true;
                }
            }
        }
        if moving_start {
            if let Some((shape, d, what)) = smallest(&self.last) {
                self.moving(shape, t0, d, what, scale);
                if d < self.threshold {
                    self.fail(shape, t0, d, what, false, scale);
                    failed = true;
                }
            }
            let speed: f64 = segments.iter().map(Segment::max_speed).sum();
            let lipschitz = self.reach * speed + self.obstacle_speed;
            let h = t1 - t0;
            for shape in 0..self.next.len() {
                let (d0, d1) = (self.last[shape].0, self.next[shape].0);
                if failed || 0.5 * (d0 + d1 - lipschitz * h) >= self.threshold {
                    continue;
                }
                self.refinements += 1;
                let dip = Dip {
                    segments,
                    shape,
                    lipschitz,
                    scale,
                };
                if let Some((time, d, unresolved)) = self.bisect(&dip, (t0, d0), (t1, d1), 0)? {
                    let what = self.next[shape].1;
                    self.fail(shape, time, d, what, unresolved, scale);
                    failed = true;
                }
            }
        }
        self.failures += u64::from(failed);
        std::mem::swap(&mut self.last, &mut self.next);
        Ok(())
    }

    /// A time in `[a, b]` at which the moving arm's shape is under the
    /// threshold (or, after [`MAX_BISECTIONS`], where the bound still
    /// allows it), if any.
    fn bisect(
        &mut self,
        dip: &Dip,
        (a, da): (f64, f64),
        (b, db): (f64, f64),
        depth: u32,
    ) -> Result<Option<(f64, f64, bool)>, SoundnessError> {
        let bound = 0.5 * (da + db - dip.lipschitz * (b - a));
        if bound >= self.threshold {
            return Ok(None);
        }
        if depth >= MAX_BISECTIONS {
            return Ok(Some((a, bound, true)));
        }
        let m = 0.5 * (a + b);
        let (dm, what) = self.shape_at(dip.segments, dip.shape, m)?;
        let moving = dip.segments.iter().any(|s| s.speed(m) > 0.0);
        if moving {
            self.moving(dip.shape, m, dm, what, dip.scale);
            if dm < self.threshold {
                return Ok(Some((m, dm, false)));
            }
        }
        if let Some(found) = self.bisect(dip, (a, da), (m, dm), depth + 1)? {
            return Ok(Some(found));
        }
        self.bisect(dip, (m, dm), (b, db), depth + 1)
    }

    fn finish(self, out: &mut Outcome) {
        out.failures = self.failures;
        out.first_failure = self.first;
        out.min_moving = self.min_moving;
        out.closest = self.closest;
        out.min_any = self.min_any;
        out.refinements = self.refinements;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_trajectory_replays_identically() {
        let params = SeparationParams {
            duration: 1.0,
            max_rays: 2000,
            ..SeparationParams::default()
        };
        let arms = SeparationArms::load(params.mount_lift).unwrap();
        let a = run_trajectory(&arms, &params, 11, 0).unwrap();
        let b = run_trajectory(&arms, &params, 11, 0).unwrap();
        assert_eq!(a, b);
        assert_eq!(a.trajectories, 1);
        assert!(a.verdicts.total() >= 49, "{:?}", a.verdicts);
        assert!(a.substeps >= 500);
    }

    /// One revolute joint about z carrying a ball at 1 m, swung through
    /// 0.2 rad in one 2 ms sub-step past a still ball: at both ends the gap
    /// is 0.072 m, at the middle 0.04 m. Only bisection sees the dip.
    fn swing(gap_above: f64) -> (u64, Option<Failure>, u64) {
        use glam::{DAffine3, DVec3};
        use shroud_guard::{Joint as ArmJoint, JointKind, Link, Shape};
        let params = SeparationParams::default();
        let arms = SeparationArms::load(params.mount_lift).unwrap();
        let scene = SeparationScene::draw(&arms, &params, 1);
        let arm = ArmModel::new(
            "swing",
            DAffine3::IDENTITY,
            vec![
                Link {
                    name: "base".into(),
                    shapes: vec![],
                },
                Link {
                    name: "bar".into(),
                    shapes: vec![Shape::sphere(DVec3::new(1.0, 0.0, 1.0), 0.05)],
                },
            ],
            vec![ArmJoint::new(
                "turn",
                JointKind::Revolute,
                [0.0, 0.0, 1.0],
                [0.0; 3],
                [0.0; 3],
                None,
            )
            .unwrap()],
        )
        .unwrap();
        let solids = [Solid {
            body: super::super::super::solids::Body::Sphere { radius: 0.05 },
            centre: DVec3::new(1.0, 0.0, 1.0 + gap_above),
            velocity: DVec3::ZERO,
            black: false,
        }];
        let mut truth = Truth::new(&arm, &solids, 0.05, 1.0, &params, &scene, Mode::Scaled);
        truth.start(&[-0.1], 0.0).unwrap();
        let mut joint = Joint::at_rest(-0.1);
        let model = StoppingModel::Deceleration(1000.0);
        let segment = joint.plan(0.0, 100.0, 100.0, &model, 100.0, 1.0);
        truth.interval(0.0, 0.002, &[segment], 1.0).unwrap();
        (truth.failures, truth.first, truth.refinements)
    }

    #[test]
    fn a_dip_between_samples_is_found_by_bisection() {
        let (failures, first, refinements) = swing(0.14);
        assert_eq!((failures, refinements), (1, 1));
        let first = first.expect("the dip is a failure");
        assert!((first.time - 0.001).abs() < 1e-9, "{first}");
        assert!((first.distance - 0.04).abs() < 1e-9, "{first}");
        assert!(!first.unresolved);
        // Further away the bound is still loose enough to bisect, and the
        // samples clear it.
        let (failures, first, refinements) = swing(0.16);
        assert_eq!((failures, refinements), (0, 1));
        assert!(first.is_none());
    }
}
