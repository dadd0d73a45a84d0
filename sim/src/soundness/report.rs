//! What a soundness run found: verdicts by kind, optimistic verdicts and
//! contacts, the conservativeness figure, and the optimistic cases
//! themselves with a class each.

use super::arms::ArmKind;
use shroud_guard::Shape;
use shroud_msg::GuardVerdict;
use shroud_surrogate::Sides;
use std::fmt;

/// Most findings a report keeps (all are counted).
pub const MAX_FINDINGS: usize = 64;

/// Verdicts by kind.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct VerdictCounts {
    pub clear: u64,
    pub stop: u64,
    pub unobserved: u64,
    pub stale: u64,
    pub no_surrogate: u64,
}

impl VerdictCounts {
    /// Counts one verdict under its kind (`no-verdict` as a stop).
    pub fn count(&mut self, verdict: GuardVerdict) {
        match verdict {
            GuardVerdict::Clear => self.clear += 1,
            GuardVerdict::Stop | GuardVerdict::NoVerdict => self.stop += 1,
            GuardVerdict::Unobserved => self.unobserved += 1,
            GuardVerdict::Stale => self.stale += 1,
            GuardVerdict::NoSurrogate => self.no_surrogate += 1,
        }
    }

    pub fn total(&self) -> u64 {
        self.clear + self.stop + self.unobserved + self.stale + self.no_surrogate
    }

    fn add(&mut self, o: &Self) {
        self.clear += o.clear;
        self.stop += o.stop;
        self.unobserved += o.unobserved;
        self.stale += o.stale;
        self.no_surrogate += o.no_surrogate;
    }
}

/// Why the view that vouched for a shape missed what came near it (judged
/// from the true geometry at that view's scan time; a heuristic, for
/// triage).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum FindingClass {
    /// The obstacle's nearest point was outside the sensor's field of view
    /// or range, under a kept triangle of its view.
    FieldOfView,
    /// It was in view but behind something (another solid, or its own near
    /// side: the space under a seen surface).
    Occlusion,
    /// It was in view and is black: no points, a hole inside kept triangles.
    BlackSolid,
    /// It was seen, and was far enough at the scan time: the motion
    /// allowance did not cover its motion.
    Timing,
    /// It was in plain view but between rays (no point near it).
    Sampling,
    Other,
}

impl FindingClass {
    pub const ALL: [FindingClass; 6] = [
        FindingClass::FieldOfView,
        FindingClass::Occlusion,
        FindingClass::BlackSolid,
        FindingClass::Timing,
        FindingClass::Sampling,
        FindingClass::Other,
    ];

    pub fn name(self) -> &'static str {
        match self {
            FindingClass::FieldOfView => "field-of-view edge inside a kept triangle",
            FindingClass::Occlusion => "occlusion inside a kept triangle",
            FindingClass::BlackSolid => "black solid inside a kept triangle",
            FindingClass::Timing => "timing",
            FindingClass::Sampling => "sampling",
            FindingClass::Other => "other",
        }
    }
}

/// One optimistic verdict, with what it takes to replay it.
#[derive(Debug, Clone, PartialEq)]
pub struct Finding {
    pub scene_seed: u64,
    pub arm: ArmKind,
    pub joints: Vec<f64>,
    /// Index of the shape in the arm's pose, and the shape.
    pub shape_index: usize,
    pub shape: Shape,
    /// Decision time on the scene clock (s).
    pub decision: f64,
    /// The combined clearance the guard gave the shape, and its minimum.
    pub clearance: f64,
    pub min_clearance: f64,
    /// True distance over [decision, decision + horizon], and to what
    /// (`None`: the floor).
    pub truth: f64,
    pub solid: Option<usize>,
    pub sampling_margin: f64,
    /// The view (sensor index) whose bound was the largest, its sides.
    pub vouching_view: Option<usize>,
    pub vouching_sides: Option<Sides>,
    pub class: FindingClass,
    /// Solids and sensors in the scene (the smaller, the simpler to study).
    pub scene_size: usize,
    /// The scene, printed.
    pub scene: String,
}

impl fmt::Display for Finding {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let what = self
            .solid
            .map_or_else(|| "the floor".to_string(), |k| format!("solid {k}"));
        writeln!(
            f,
            "[{}] scene seed {:#x}, arm {:?}, joints {:.4?}",
            self.class.name(),
            self.scene_seed,
            self.arm,
            self.joints
        )?;
        writeln!(
            f,
            "  shape {}: {:?}\n  decision at {:.4} s: guard clearance {:.4} m (min {:.4} m), \
             true distance {:.4} m to {what}, sampling margin {:.4} m, vouching view {:?} ({:?})",
            self.shape_index,
            self.shape,
            self.decision,
            self.clearance,
            self.min_clearance,
            self.truth,
            self.sampling_margin,
            self.vouching_view,
            self.vouching_sides
        )?;
        write!(f, "{}", self.scene)
    }
}

/// Counts of a run (or of one scene; reports add up).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SoundnessReport {
    pub scenes: u64,
    /// Sensors whose cloud became a view, and those whose did not (too few
    /// points, or the fit or envelope refused it).
    pub views: u64,
    pub views_missing: u64,
    pub points: u64,
    pub verdicts: VerdictCounts,
    /// Clear verdicts with a true distance below stop distance less the
    /// sampling margin, and those with a true distance <= 0.
    pub optimistic: u64,
    pub contacts: u64,
    /// Per [`FindingClass::ALL`], optimistic verdicts of that class.
    pub classes: [u64; 6],
    /// Verdicts (clear, stop or unobserved) for poses farther than twice the
    /// stop distance from everything and in view of some sensor; those of
    /// them that were not clear.
    pub eligible: u64,
    pub eligible_stopped: u64,
    /// Of those, the verdicts that were `unobserved`.
    pub eligible_unobserved: u64,
    /// Eligible verdicts whose true distance is within the stop distance
    /// plus the motion allowance of the freshest view (speed bound times its
    /// age and the horizon): no guard fed these views may clear them, since
    /// an obstacle it has not seen yet may be that close. And of them, those
    /// not clear.
    pub eligible_forced: u64,
    pub eligible_forced_stopped: u64,
    /// Largest sampling margin of any scene's views.
    pub max_sampling_margin: f64,
    /// Smallest true distance of a clear verdict (m).
    pub closest_clear: f64,
    /// The first [`MAX_FINDINGS`] optimistic verdicts.
    pub findings: Vec<Finding>,
}

impl SoundnessReport {
    pub fn empty() -> Self {
        Self {
            closest_clear: f64::INFINITY,
            ..Self::default()
        }
    }

    /// Share of eligible verdicts that were not clear (`None`: none eligible).
    pub fn conservativeness(&self) -> Option<f64> {
        (self.eligible > 0).then(|| self.eligible_stopped as f64 / self.eligible as f64)
    }

    /// [`Self::conservativeness`] over the eligible verdicts that the motion
    /// allowance does not force to stop.
    pub fn conservativeness_beyond_allowance(&self) -> Option<f64> {
        let n = self.eligible - self.eligible_forced;
        (n > 0).then(|| (self.eligible_stopped - self.eligible_forced_stopped) as f64 / n as f64)
    }

    /// This report and `other` together.
    pub fn merged(mut self, other: Self) -> Self {
        self.scenes += other.scenes;
        self.views += other.views;
        self.views_missing += other.views_missing;
        self.points += other.points;
        self.verdicts.add(&other.verdicts);
        self.optimistic += other.optimistic;
        self.contacts += other.contacts;
        for (a, b) in self.classes.iter_mut().zip(other.classes) {
            *a += b;
        }
        self.eligible += other.eligible;
        self.eligible_stopped += other.eligible_stopped;
        self.eligible_unobserved += other.eligible_unobserved;
        self.eligible_forced += other.eligible_forced;
        self.eligible_forced_stopped += other.eligible_forced_stopped;
        self.max_sampling_margin = self.max_sampling_margin.max(other.max_sampling_margin);
        self.closest_clear = self.closest_clear.min(other.closest_clear);
        let room = MAX_FINDINGS.saturating_sub(self.findings.len());
        self.findings.extend(other.findings.into_iter().take(room));
        self
    }

    /// Per class, the kept finding with the smallest scene (the simplest to
    /// study), ties to the smaller seed.
    pub fn simplest_findings(&self) -> Vec<&Finding> {
        FindingClass::ALL
            .iter()
            .filter_map(|&c| {
                self.findings
                    .iter()
                    .filter(|f| f.class == c)
                    .min_by_key(|f| (f.scene_size, f.scene_seed))
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reports_add_up() {
        let mut a = SoundnessReport::empty();
        a.scenes = 1;
        a.verdicts.clear = 3;
        a.eligible = 4;
        a.eligible_stopped = 1;
        a.eligible_forced = 2;
        a.eligible_forced_stopped = 1;
        a.closest_clear = 0.5;
        let mut b = SoundnessReport::empty();
        b.scenes = 2;
        b.verdicts.stop = 2;
        b.classes[1] = 1;
        b.closest_clear = 0.3;
        let m = a.merged(b);
        assert_eq!(m.scenes, 3);
        assert_eq!(m.verdicts.total(), 5);
        assert_eq!(m.classes[1], 1);
        assert_eq!(m.closest_clear, 0.3);
        assert_eq!(m.conservativeness(), Some(0.25));
        assert_eq!(m.conservativeness_beyond_allowance(), Some(0.0));
        assert_eq!(SoundnessReport::empty().conservativeness(), None);
    }
}
