//! What a separation run found: verdicts by kind and scale, failures (the
//! first one replayable), the smallest separations, and the productivity of
//! the scaled guard against the binary one.

use super::super::arms::ArmKind;
use super::super::report::VerdictCounts;
use super::SeparationParams;
use std::fmt;

/// Which guard drove the arm.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Mode {
    /// The verdict's scale, as `decide_moving` gives it.
    Scaled,
    /// A binary stop at the same safety: a verdict moves the arm (at full
    /// speed) only when its scale is 1, i.e. when the full-speed bound holds.
    Binary,
}

/// Time and progress of the arm under one guard.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ModeStats {
    pub trajectories: u64,
    /// Simulated seconds.
    pub seconds: f64,
    /// The integral of the scale the arm obeyed (0 while halted).
    pub scale_seconds: f64,
    /// Seconds of the trajectory done at nominal speed.
    pub progress: f64,
    /// Seconds during which some joint moved.
    pub moving_seconds: f64,
    /// Trajectories whose first `task` nominal seconds were done within
    /// their time, and the sum of the times they took.
    pub tasks_done: u64,
    pub task_seconds: f64,
}

impl ModeStats {
    fn add(&mut self, o: &Self) {
        self.trajectories += o.trajectories;
        self.seconds += o.seconds;
        self.scale_seconds += o.scale_seconds;
        self.progress += o.progress;
        self.moving_seconds += o.moving_seconds;
        self.tasks_done += o.tasks_done;
        self.task_seconds += o.task_seconds;
    }

    /// The scale the arm ran at, averaged over time.
    pub fn mean_scale(&self) -> f64 {
        self.scale_seconds / self.seconds.max(1e-300)
    }

    /// Nominal trajectory seconds done per second.
    pub fn progress_rate(&self) -> f64 {
        self.progress / self.seconds.max(1e-300)
    }

    /// Share of trajectories that finished the task.
    pub fn task_share(&self) -> f64 {
        self.tasks_done as f64 / (self.trajectories.max(1)) as f64
    }

    /// Mean time of the finished tasks (s).
    pub fn mean_task_time(&self) -> Option<f64> {
        (self.tasks_done > 0).then(|| self.task_seconds / self.tasks_done as f64)
    }
}

/// One guard's figures on all trajectories and on those with a person.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Productivity {
    pub all: ModeStats,
    pub crossing: ModeStats,
}

impl Productivity {
    fn add(&mut self, o: &Self) {
        self.all.add(&o.all);
        self.crossing.add(&o.crossing);
    }
}

/// An instant at which the moving arm was nearer to something than the
/// threshold, with what it takes to replay it.
#[derive(Debug, Clone, PartialEq)]
pub struct Failure {
    /// The trajectory's index in the run and its seed
    /// ([`super::run_trajectory`] replays it alone).
    pub index: u64,
    pub seed: u64,
    pub mode: Mode,
    pub arm: ArmKind,
    /// Simulated time (s).
    pub time: f64,
    pub link: String,
    /// Index of the shape in the arm's pose.
    pub shape: usize,
    /// True distance, and the threshold (`C` less the sampling margin).
    pub distance: f64,
    pub threshold: f64,
    /// What it came near: a solid, the person or the floor.
    pub obstacle: String,
    /// The Lipschitz bound could not be resolved by bisection (no sample
    /// below the threshold was found, but none above it either): counted as
    /// a failure all the same.
    pub unresolved: bool,
    /// The scale the arm obeyed then.
    pub scale: f64,
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "trajectory {} (seed {:#x}, {:?} guard, arm {:?}) at {:.4} s: link {} (shape {}) {:.4} m from {} \
             while moving at scale {:.3}, threshold {:.4} m{}",
            self.index,
            self.seed,
            self.mode,
            self.arm,
            self.time,
            self.link,
            self.shape,
            self.distance,
            self.obstacle,
            self.scale,
            self.threshold,
            if self.unresolved {
                " (not resolved by bisection)"
            } else {
                ""
            }
        )
    }
}

/// Counts of a run (or of one trajectory; reports add up).
#[derive(Debug, Clone, PartialEq)]
pub struct SeparationReport {
    pub trajectories: u64,
    /// Trajectories with a person walking across.
    pub crossings: u64,
    /// Scans, those that became a view, and the points scanned.
    pub scans: u64,
    pub views: u64,
    pub points: u64,
    /// The scaled guard's verdicts by kind, and its clear verdicts at scale
    /// 1 and strictly between 0 and 1, and the smallest of those scales.
    pub verdicts: VerdictCounts,
    pub full_speed: u64,
    pub scaled: u64,
    pub smallest_scale: f64,
    /// The binary guard's verdicts: clear (full speed) and not.
    pub binary_clear: u64,
    pub binary_stop: u64,
    /// Sub-steps (of both guards) during which the moving arm came nearer
    /// than the threshold, per guard, and the trajectories with one.
    pub failures: u64,
    pub binary_failures: u64,
    pub failing_trajectories: u64,
    /// The failure of the lowest trajectory index (and the earliest in it).
    pub first_failure: Option<Failure>,
    /// The smallest true separation while the arm moved, per guard, and at
    /// any time.
    pub min_separation_moving: f64,
    pub binary_min_separation_moving: f64,
    pub min_separation: f64,
    /// The moment of the scaled guard's smallest separation while moving.
    pub closest: Option<Failure>,
    /// The largest sampling margin of a scene, and the smallest threshold.
    pub max_margin: f64,
    pub min_threshold: f64,
    /// Sub-step intervals bisected because the Lipschitz bound came near
    /// the threshold, and sub-steps simulated (both guards).
    pub refinements: u64,
    pub substeps: u64,
    pub scaled_mode: Productivity,
    pub binary_mode: Productivity,
}

impl SeparationReport {
    pub fn empty() -> Self {
        Self {
            trajectories: 0,
            crossings: 0,
            scans: 0,
            views: 0,
            points: 0,
            verdicts: VerdictCounts::default(),
            full_speed: 0,
            scaled: 0,
            smallest_scale: f64::INFINITY,
            binary_clear: 0,
            binary_stop: 0,
            failures: 0,
            binary_failures: 0,
            failing_trajectories: 0,
            first_failure: None,
            min_separation_moving: f64::INFINITY,
            binary_min_separation_moving: f64::INFINITY,
            min_separation: f64::INFINITY,
            closest: None,
            max_margin: 0.0,
            min_threshold: f64::INFINITY,
            refinements: 0,
            substeps: 0,
            scaled_mode: Productivity::default(),
            binary_mode: Productivity::default(),
        }
    }

    /// This report and `other` together.
    pub fn merged(mut self, o: Self) -> Self {
        self.trajectories += o.trajectories;
        self.crossings += o.crossings;
        self.scans += o.scans;
        self.views += o.views;
        self.points += o.points;
        let (v, w) = (&mut self.verdicts, &o.verdicts);
        v.clear += w.clear;
        v.stop += w.stop;
        v.unobserved += w.unobserved;
        v.stale += w.stale;
        v.no_surrogate += w.no_surrogate;
        self.full_speed += o.full_speed;
        self.scaled += o.scaled;
        self.smallest_scale = self.smallest_scale.min(o.smallest_scale);
        self.binary_clear += o.binary_clear;
        self.binary_stop += o.binary_stop;
        self.failures += o.failures;
        self.binary_failures += o.binary_failures;
        self.failing_trajectories += o.failing_trajectories;
        self.first_failure = match (self.first_failure.take(), o.first_failure) {
            (Some(a), Some(b)) => Some(if (b.index, b.mode) < (a.index, a.mode) {
                b
            } else {
                a
            }),
            (a, b) => a.or(b),
        };
        if o.min_separation_moving < self.min_separation_moving {
            self.closest = o.closest;
        }
        self.min_separation_moving = self.min_separation_moving.min(o.min_separation_moving);
        self.binary_min_separation_moving = self
            .binary_min_separation_moving
            .min(o.binary_min_separation_moving);
        self.min_separation = self.min_separation.min(o.min_separation);
        self.max_margin = self.max_margin.max(o.max_margin);
        self.min_threshold = self.min_threshold.min(o.min_threshold);
        self.refinements += o.refinements;
        self.substeps += o.substeps;
        self.scaled_mode.add(&o.scaled_mode);
        self.binary_mode.add(&o.binary_mode);
        self
    }

    /// Every verdict both guards gave.
    pub fn decisions(&self) -> u64 {
        self.verdicts.total() + self.binary_clear + self.binary_stop
    }

    /// The run as a markdown table; `extra` rows (the command, the wall
    /// time) are appended.
    pub fn table(&self, params: &SeparationParams, extra: &[(String, String)]) -> String {
        let v = &self.verdicts;
        let total = v.total();
        let share = |n: u64, of: u64| {
            if of == 0 {
                0.0
            } else {
                100.0 * n as f64 / of as f64
            }
        };
        let metres = |x: f64| {
            if x.is_finite() {
                format!("{x:.4} m")
            } else {
                "n/a".into()
            }
        };
        // One guard's figures on one set of trajectories.
        let figures = |m: &ModeStats| {
            let per_second = if m.progress > 0.0 {
                format!("{:.1} s", m.seconds / m.progress)
            } else {
                "never".into()
            };
            format!(
                "mean scale {:.3}, moving {:.1} % of the time, {per_second} per nominal second of \
                 trajectory; the first {} s of it done in {:.1} % of the trajectories{}",
                m.mean_scale(),
                100.0 * m.moving_seconds / m.seconds.max(1e-300),
                params.task,
                100.0 * m.task_share(),
                m.mean_task_time()
                    .map_or(String::new(), |t| format!(" (after {t:.2} s on average)")),
            )
        };
        let productivity = |all: bool| {
            let pick = |p: &Productivity| if all { p.all } else { p.crossing };
            let (s, b) = (pick(&self.scaled_mode), pick(&self.binary_mode));
            if s.trajectories == 0 {
                return "n/a (none)".to_string();
            }
            let mut text = format!("**scaled**: {}", figures(&s));
            if b.trajectories > 0 {
                let kept = if b.progress > 0.0 {
                    format!("{:.2}x the binary's", s.progress / b.progress)
                } else {
                    "the binary made none".into()
                };
                text.push_str(&format!(
                    "; **binary**: {}; the scaled progress is {kept}",
                    figures(&b)
                ));
            }
            text
        };
        let mut rows: Vec<(String, String)> = vec![
            (
                "trajectories".into(),
                format!(
                    "{} ({} with a person crossing), {:.0} s simulated per guard",
                    self.trajectories, self.crossings, self.scaled_mode.all.seconds
                ),
            ),
            (
                "scans / views fitted".into(),
                format!(
                    "{} / {} ({} points)",
                    self.scans, self.views, self.points
                ),
            ),
            (
                "verdicts (scaled guard)".into(),
                format!("{total} ({} decisions of both guards)", self.decisions()),
            ),
            (
                "clear at full speed".into(),
                format!(
                    "{} ({:.1} %)",
                    self.full_speed,
                    share(self.full_speed, total)
                ),
            ),
            (
                "clear at a scale in (0, 1)".into(),
                format!(
                    "{} ({:.1} %), smallest {}",
                    self.scaled,
                    share(self.scaled, total),
                    if self.smallest_scale.is_finite() {
                        format!("{:.4}", self.smallest_scale)
                    } else {
                        "n/a".into()
                    }
                ),
            ),
            (
                "stop".into(),
                format!("{} ({:.1} %)", v.stop, share(v.stop, total)),
            ),
            (
                "unobserved".into(),
                format!("{} ({:.1} %)", v.unobserved, share(v.unobserved, total)),
            ),
            (
                "stale".into(),
                format!("{} ({:.1} %)", v.stale, share(v.stale, total)),
            ),
            (
                "no surrogate".into(),
                format!("{} ({:.1} %)", v.no_surrogate, share(v.no_surrogate, total)),
            ),
            (
                "binary guard: clear / stop".into(),
                format!(
                    "{} / {} ({:.1} % clear)",
                    self.binary_clear,
                    self.binary_stop,
                    share(self.binary_clear, self.binary_clear + self.binary_stop)
                ),
            ),
            (
                "**failures** (scaled / binary)".into(),
                format!(
                    "**{} / {}** ({} trajectories)",
                    self.failures, self.binary_failures, self.failing_trajectories
                ),
            ),
            (
                "smallest separation while moving (scaled / binary)".into(),
                format!(
                    "{} / {}",
                    metres(self.min_separation_moving),
                    metres(self.binary_min_separation_moving)
                ),
            ),
            (
                "smallest separation at any time".into(),
                metres(self.min_separation),
            ),
            (
                "threshold (C less the sampling margin)".into(),
                format!(
                    "C = {} m; largest sampling margin {}, so the threshold is at least {}",
                    params.stop_distance,
                    metres(self.max_margin),
                    metres(self.min_threshold)
                ),
            ),
            (
                "sub-steps / bisected".into(),
                format!("{} / {}", self.substeps, self.refinements),
            ),
            (
                "productivity, all trajectories".into(),
                productivity(true),
            ),
            (
                "productivity, person crossing".into(),
                productivity(false),
            ),
            (
                "parameters".into(),
                format!(
                    "C {} m, obstacle speed <= {} m/s, horizon {} s, max age {} s, {} s per trajectory, \
                     joint states at {} Hz ({:.0} % with velocities), scans at {}-{} Hz, <= {} rays per scan, \
                     {} rays, sandwich share {}, person share {}, mount lift {} m, waypoints >= {} m up, \
                     step {} s, arm {:?}{}",
                    params.stop_distance,
                    params.obstacle_speed,
                    params.horizon,
                    params.max_age,
                    params.duration,
                    params.joint_rate,
                    100.0 * params.velocities_share,
                    params.scan_rate_min,
                    params.scan_rate_max,
                    params.max_rays,
                    if params.parallel_rays {
                        "parallel"
                    } else {
                        "perspective"
                    },
                    params.sandwich_share,
                    params.person_share,
                    params.mount_lift,
                    params.min_height,
                    params.step,
                    params.behaviour,
                    params
                        .declared_obstacle_speed
                        .map_or(String::new(), |v| format!(", the guard told {v} m/s"))
                ),
            ),
        ];
        if let Some(c) = &self.closest {
            rows.push((
                "closest approach while moving (scaled)".into(),
                c.to_string(),
            ));
        }
        if let Some(f) = &self.first_failure {
            rows.push(("first failure".into(), f.to_string()));
        }
        rows.extend(extra.iter().cloned());
        let mut out = String::from("| guard separation | |\n| --- | --- |\n");
        for (name, value) in rows {
            out.push_str(&format!("| {name} | {value} |\n"));
        }
        out
    }
}
