//! [`CollisionGuard`]: the latest surrogate per view in, a verdict per arm pose out.

use super::combine::{combine, ViewReport};
use super::policy::{GuardPolicy, UnobservedPolicy};
use super::speed_control::SpeedControl;
use super::view::{check_skew, HeldSurrogate, SurrogateInput, SurrogateRejected};
use crate::report::{shape_clearances, validate_shapes};
use crate::{GuardConfig, GuardError, GuardReport, SpeedScale, WorldShape};
use shroud_msg::{counted_transit, CollisionMessage, GuardVerdict, LinkClearance};

/// The guard's state: per view its latest accepted surrogate.
#[derive(Debug, Clone)]
pub struct CollisionGuard {
    views: Vec<String>,
    held: Vec<Option<HeldSurrogate>>,
    pub(super) links: Vec<String>,
    pub(super) policy: GuardPolicy,
    pub(super) config: GuardConfig,
    /// Speed and separation monitoring, when the arm's motion is known.
    pub(super) speed: Option<SpeedControl>,
}

/// The verdict for one arm pose, with what it was based on.
#[derive(Debug, Clone, PartialEq)]
pub struct Decision {
    pub verdict: GuardVerdict,
    /// Why, for a person (empty when clear).
    pub reason: String,
    /// Combined clearances (after motion allowances; a shape's
    /// `unobserved` means its bound is set by unseen space in every fresh
    /// view); `None` without a fresh view.
    pub report: Option<GuardReport>,
    /// Fresh views used.
    pub views: usize,
    /// The oldest view used (for `stale`, the newest one held), for the record.
    pub oldest: Option<SurrogateRecord>,
    /// The speed scale: 1 for `clear` and 0 otherwise from [`CollisionGuard::decide`];
    /// [`CollisionGuard::decide_moving`] scales it.
    pub speed: SpeedScale,
}

/// Which surrogate a decision rests on: its source cloud's stamp (the
/// device's word) and sequence, and its age at the decision.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SurrogateRecord {
    pub stamp_ns: u64,
    pub sequence: u64,
    pub age_ns: u64,
}

impl Decision {
    /// The answer to a joint state that could not be checked: stop, and say why.
    pub fn refused(reason: impl Into<String>) -> Self {
        Self {
            verdict: GuardVerdict::Stop,
            reason: reason.into(),
            report: None,
            views: 0,
            oldest: None,
            speed: SpeedScale::binary(false, 0.0),
        }
    }

    /// Turns the decision into a `stop` for `reason`, at scale 0.
    pub fn stop(&mut self, reason: String) {
        self.verdict = GuardVerdict::Stop;
        self.reason = reason;
        self.speed.scale = 0.0;
    }
}

impl CollisionGuard {
    /// A guard over the named views for an arm with the named links.
    ///
    /// Clearances are capped at `max_report` before the motion allowance is
    /// subtracted, so `max_report` is raised to at least `stop_distance +
    /// max_obstacle_speed * (max_age + horizon)`: otherwise any surrogate
    /// older than `(max_report - stop_distance) / speed - horizon` would stop
    /// the arm in empty space. (A view's age includes its clock offset, so
    /// `max_age` bounds it; each view's position error raises its own cap
    /// when it is checked.)
    pub fn new(
        views: Vec<String>,
        links: Vec<String>,
        policy: GuardPolicy,
        mut config: GuardConfig,
    ) -> Result<Self, GuardError> {
        policy.validate()?;
        config.validate()?;
        let reach = config.max_obstacle_speed * (policy.max_age_ns as f64 * 1e-9 + config.horizon);
        config.max_report = config.max_report.max(config.stop_distance + reach);
        if views.is_empty() {
            return Err(GuardError::BadConfig(
                "the guard needs at least one view".into(),
            ));
        }
        if let Some(dup) = views
            .iter()
            .enumerate()
            .find(|(i, v)| views[..*i].contains(v))
        {
            return Err(GuardError::BadConfig(format!(
                "view {:?} is given twice",
                dup.1
            )));
        }
        Ok(Self {
            held: vec![None; views.len()],
            views,
            links,
            policy,
            config,
            speed: None,
        })
    }

    pub fn views(&self) -> &[String] {
        &self.views
    }

    pub fn config(&self) -> &GuardConfig {
        &self.config
    }

    pub fn policy(&self) -> &GuardPolicy {
        &self.policy
    }

    /// Forgets `view`'s surrogate: a newer one arrived that could not be used
    /// (corrupted, uncertified), so the older one no longer vouches.
    pub fn invalidate(&mut self, view: usize) {
        if let Some(slot) = self.held.get_mut(view) {
            *slot = None;
        }
    }

    /// Takes a surrogate of `view` that reached the guard at `arrived_ns`
    /// (monotonic) and `wall_ns` (the guard's wall clock, read together),
    /// unless its timing cannot be trusted (its source stamp too far from
    /// `wall_ns`, or its publication further in the future than the clock
    /// offset bound) or its position error is not a distance: then the view
    /// is emptied, since newer data exists that cannot be used.
    pub fn accept(
        &mut self,
        view: usize,
        input: SurrogateInput,
        arrived_ns: u64,
        wall_ns: u64,
    ) -> Result<(), SurrogateRejected> {
        let slot = self
            .held
            .get_mut(view)
            .ok_or(SurrogateRejected::UnknownView(view))?;
        let timed = check_skew(input.stamp_ns, wall_ns, &self.policy).and_then(|()| {
            if !(input.position_error.is_finite() && input.position_error >= 0.0) {
                return Err(SurrogateRejected::BadPositionError(input.position_error));
            }
            counted_transit(input.published_ns, wall_ns, self.policy.max_clock_offset_ns)
                .map_err(SurrogateRejected::ClockOffset)
        });
        match timed {
            Ok(transit_ns) => {
                *slot = Some(HeldSurrogate {
                    input,
                    arrived_ns,
                    transit_ns,
                });
                Ok(())
            }
            Err(refused) => {
                *slot = None;
                Err(refused)
            }
        }
    }

    /// The verdict for world `shapes` (carried by links `0..links`) at `now_ns`.
    pub fn decide(&self, shapes: &[WorldShape], now_ns: u64) -> Result<Decision, GuardError> {
        let held: Vec<&HeldSurrogate> = self.held.iter().flatten().collect();
        if held.is_empty() {
            let reason = format!("no usable surrogate on {}", self.views.join(", "));
            return Ok(self.without_report(GuardVerdict::NoSurrogate, reason, None));
        }
        let fresh: Vec<&HeldSurrogate> = held
            .iter()
            .copied()
            .filter(|h| h.age_ns(now_ns) <= self.policy.max_age_ns)
            .collect();
        if fresh.is_empty() {
            let newest = held.iter().min_by_key(|h| h.age_ns(now_ns)).copied();
            return Ok(self.stale(newest, now_ns));
        }
        let mut reports = Vec::with_capacity(fresh.len());
        for (i, h) in fresh.iter().enumerate() {
            // A view whose cloud may be misplaced looks that much further
            // (at most twice as far), so that subtracting the error from a
            // capped clearance does not stop the arm in empty space.
            let config = GuardConfig {
                max_report: self.config.max_report
                    + h.input.position_error.min(self.config.max_report),
                ..self.config
            };
            config.validate()?;
            if i == 0 {
                // The same shapes for every view: checked once, where the
                // first view's check would refuse them.
                validate_shapes(shapes, self.links.len())?;
            }
            let unseen_counts = self.policy.unobserved == UnobservedPolicy::Stop;
            let envelope = &h.input.envelope;
            // Per shape only: the views combine shape by shape.
            reports.push(ViewReport {
                shapes: shape_clearances(envelope, shapes, &config, unseen_counts),
                allowance: self.allowance(h, now_ns),
            });
        }
        let report = combine(
            &reports,
            self.links.len(),
            &self.config,
            self.policy.unobserved,
        );
        let oldest = fresh
            .iter()
            .max_by_key(|h| h.age_ns(now_ns))
            .map(|h| record(h, now_ns));
        let (verdict, reason) = self.judge(&report);
        Ok(Decision {
            verdict,
            reason,
            report: Some(report),
            views: fresh.len(),
            oldest,
            speed: SpeedScale::binary(verdict == GuardVerdict::Clear, self.config.stop_distance),
        })
    }

    /// How far an obstacle may have moved from where a view's cloud saw it,
    /// until the arm stops moving on this verdict: the speed bound times the
    /// data's age and the horizon, plus how far the sensor may have misplaced
    /// it.
    fn allowance(&self, h: &HeldSurrogate, now_ns: u64) -> f64 {
        let seconds = h.age_ns(now_ns) as f64 * 1e-9 + self.config.horizon;
        self.config.max_obstacle_speed * seconds + h.input.position_error
    }

    fn judge(&self, report: &GuardReport) -> (GuardVerdict, String) {
        let link = |i: Option<usize>| {
            i.and_then(|i| self.links.get(i))
                .map_or("?", String::as_str)
                .to_owned()
        };
        let counts_unseen = self.policy.unobserved == UnobservedPolicy::Stop;
        if report.stop && report.unobserved && counts_unseen {
            let reason = format!(
                "link {} is {:.3} m from space no fresh view saw (stop distance {:.3} m)",
                link(report.closest_link),
                report.min_clearance,
                self.config.stop_distance
            );
            return (GuardVerdict::Unobserved, reason);
        }
        if report.stop {
            let reason = format!(
                "link {} at {:.3} m, within the stop distance {:.3} m",
                link(report.closest_link),
                report.min_clearance,
                self.config.stop_distance
            );
            return (GuardVerdict::Stop, reason);
        }
        (GuardVerdict::Clear, String::new())
    }

    fn stale(&self, newest: Option<&HeldSurrogate>, now_ns: u64) -> Decision {
        let age = newest.map_or(0, |h| h.age_ns(now_ns));
        let reason = format!(
            "newest surrogate is {:.3} s old (max {:.3} s)",
            age as f64 / 1e9,
            self.policy.max_age_ns as f64 / 1e9
        );
        self.without_report(
            GuardVerdict::Stale,
            reason,
            newest.map(|h| record(h, now_ns)),
        )
    }

    fn without_report(
        &self,
        verdict: GuardVerdict,
        reason: String,
        oldest: Option<SurrogateRecord>,
    ) -> Decision {
        Decision {
            verdict,
            reason,
            report: None,
            views: 0,
            oldest,
            speed: SpeedScale::binary(false, self.config.stop_distance),
        }
    }

    /// The wire message of `decision` for joint state (`stamp`, `sequence`).
    pub fn message(
        &self,
        decision: &Decision,
        arm: &str,
        (joints_stamp_ns, joints_sequence): (u64, u64),
        check_ns: u64,
    ) -> CollisionMessage {
        let record = decision.oldest.unwrap_or_default();
        let (min_clearance, closest_link, links, unobserved) = match &decision.report {
            Some(r) => (
                r.min_clearance,
                r.closest_link
                    .and_then(|i| self.links.get(i))
                    .cloned()
                    .unwrap_or_default(),
                self.link_clearances(r),
                r.shapes.iter().any(|s| s.unobserved),
            ),
            // Without a usable surrogate nothing is known to be clear.
            None => (0.0, String::new(), Vec::new(), false),
        };
        CollisionMessage {
            version: CollisionMessage::VERSION,
            joints_stamp_ns,
            joints_sequence,
            arm: arm.to_owned(),
            surrogate_stamp_ns: record.stamp_ns,
            surrogate_sequence: record.sequence,
            surrogate_age_ns: record.age_ns,
            views: decision.views as u32,
            verdict: decision.verdict,
            stop: decision.verdict != GuardVerdict::Clear,
            reason: decision.reason.clone(),
            stop_distance: self.config.stop_distance,
            min_clearance,
            closest_link,
            unobserved,
            links,
            check_ns,
            speed_scale: decision.speed.scale,
            limiting_link: decision
                .speed
                .limiting_link
                .and_then(|i| self.links.get(i))
                .cloned()
                .unwrap_or_default(),
            protective_distance: decision
                .speed
                .protective_distance
                .max(self.config.stop_distance),
        }
    }

    fn link_clearances(&self, r: &GuardReport) -> Vec<LinkClearance> {
        self.links
            .iter()
            .enumerate()
            .map(|(i, name)| LinkClearance {
                link: name.clone(),
                clearance: r.links.get(i).copied().unwrap_or(0.0),
                unobserved: r.shapes.iter().any(|s| s.link == i && s.unobserved),
            })
            .collect()
    }
}

fn record(h: &HeldSurrogate, now_ns: u64) -> SurrogateRecord {
    SurrogateRecord {
        stamp_ns: h.input.stamp_ns,
        sequence: h.input.sequence,
        age_ns: h.age_ns(now_ns),
    }
}
