//! The arm file (TOML): the arm, optionally a trajectory for a simulated arm and
//! the guard settings. Lengths in metres, angles in radians.
//!
//! ```toml
//! name = "demo_arm"                  # optional, default "arm"
//!
//! [base]                             # optional, default identity: world pose of link 0
//! xyz = [0.0, 0.0, 1.6]              # translation
//! rpy = [3.141592653589793, 0.0, 0.0]  # roll, pitch, yaw (URDF: Rz(yaw) Ry(pitch) Rx(roll))
//!
//! [[links]]                          # links in chain order; joints + 1 of them
//! name = "base_link"
//! spheres = [{ centre = [0.0, 0.0, 0.05], radius = 0.08 }]      # optional, link frame
//! capsules = [{ a = [0.0, 0.0, 0.0], b = [0.0, 0.0, 0.3], radius = 0.05 }]  # optional
//!
//! [[joints]]                         # joint i moves links[i + 1] relative to links[i]
//! name = "shoulder_pan"
//! kind = "revolute"                  # revolute | prismatic | fixed
//! parent = "base_link"               # optional; checked against the chain order
//! child = "shoulder"                 # optional; checked against the chain order
//! xyz = [0.0, 0.0, 0.1]              # origin: child frame in parent frame at q = 0 (default 0)
//! rpy = [0.0, 0.0, 0.0]              # (default 0)
//! axis = [0.0, 0.0, 1.0]             # required unless fixed; in the child frame; normalised
//! limits = [-3.14, 3.14]             # optional [lower, upper]; not allowed on fixed joints
//!
//! [trajectory]                       # optional; one value per non-fixed joint
//! looping = true                     # default true
//! waypoints = [
//!   { positions = [0.0, 0.5, 1.0, 0.0, 0.0, 0.0], duration = 2.0 },  # seconds to the next one
//! ]
//!
//! [guard]                            # optional; these are the defaults
//! stop_distance = 0.05
//! max_report = 0.2
//! refine_depth = 3
//! max_obstacle_speed = 0.0            # m/s; clearances shrink by this times (age + horizon)
//! horizon = 0.1                       # s; the arm moves at most this long on a verdict
//!
//! [motion]                           # optional: speed and separation monitoring,
//! reaction_time = 0.1                # see `separation::file` for the whole table
//! joints = [{ name = "shoulder_pan", max_velocity = 1.5, deceleration = 6.0 }]
//! ```
//!
//! A link's shapes are its spheres, then its capsules, in file order. Unknown keys
//! are errors, so typos do not pass silently.

use super::arm::{ArmModel, Link};
use super::config::GuardConfig;
use super::error::GuardError;
use super::joint::{origin_from_xyz_rpy, Joint, JointKind};
use super::separation::{ArmMotion, RawMotion};
use super::shape::Shape;
use super::trajectory::{Trajectory, Waypoint};
use glam::DVec3;
use serde::Deserialize;

/// Everything an arm file holds, validated.
#[derive(Debug, Clone, PartialEq)]
pub struct ArmFile {
    pub arm: ArmModel,
    /// Validated against the arm (joint count and limits).
    pub trajectory: Option<Trajectory>,
    /// `GuardConfig::default()` when the file has no `[guard]` table.
    pub guard: GuardConfig,
    /// The `[motion]` table, validated against the arm: without it the guard
    /// cannot bound the arm's own motion and does not scale its speed.
    pub motion: Option<ArmMotion>,
}

impl ArmFile {
    pub fn from_toml_str(text: &str) -> Result<Self, GuardError> {
        let raw: RawFile = toml::from_str(text).map_err(|e| GuardError::Toml(e.to_string()))?;
        let arm = raw.arm()?;
        let trajectory = raw
            .trajectory
            .map(|t| {
                let waypoints = t
                    .waypoints
                    .into_iter()
                    .map(|w| Waypoint {
                        positions: w.positions,
                        duration: w.duration,
                    })
                    .collect();
                Trajectory::for_arm(waypoints, t.looping, &arm)
            })
            .transpose()?;
        let guard = raw.guard.unwrap_or_default();
        guard.validate()?;
        let motion = raw.motion.map(|m| m.for_arm(&arm)).transpose()?;
        if let (Some(motion), Some(trajectory)) = (&motion, &trajectory) {
            motion.check_trajectory(&arm, trajectory)?;
        }
        Ok(Self {
            arm,
            trajectory,
            guard,
            motion,
        })
    }
}

impl ArmModel {
    /// Parses and validates an arm file (see the module docs for the schema);
    /// its `[trajectory]` and `[guard]` tables are checked too, then dropped.
    pub fn from_toml_str(text: &str) -> Result<ArmModel, GuardError> {
        Ok(ArmFile::from_toml_str(text)?.arm)
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFile {
    #[serde(default = "default_name")]
    name: String,
    #[serde(default)]
    base: RawPose,
    links: Vec<RawLink>,
    #[serde(default)]
    joints: Vec<RawJoint>,
    trajectory: Option<RawTrajectory>,
    guard: Option<GuardConfig>,
    motion: Option<RawMotion>,
}

fn default_name() -> String {
    "arm".into()
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPose {
    #[serde(default)]
    xyz: [f64; 3],
    #[serde(default)]
    rpy: [f64; 3],
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLink {
    name: String,
    #[serde(default)]
    spheres: Vec<RawSphere>,
    #[serde(default)]
    capsules: Vec<RawCapsule>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSphere {
    centre: [f64; 3],
    radius: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCapsule {
    a: [f64; 3],
    b: [f64; 3],
    radius: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawJoint {
    name: String,
    kind: JointKind,
    parent: Option<String>,
    child: Option<String>,
    #[serde(default)]
    xyz: [f64; 3],
    #[serde(default)]
    rpy: [f64; 3],
    axis: Option<[f64; 3]>,
    limits: Option<[f64; 2]>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawTrajectory {
    #[serde(default = "default_looping")]
    looping: bool,
    waypoints: Vec<RawWaypoint>,
}

fn default_looping() -> bool {
    true
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawWaypoint {
    positions: Vec<f64>,
    duration: f64,
}

impl RawFile {
    fn arm(&self) -> Result<ArmModel, GuardError> {
        let base = origin_from_xyz_rpy("base", self.base.xyz, self.base.rpy)?;
        let links = self
            .links
            .iter()
            .map(|l| {
                let spheres = l
                    .spheres
                    .iter()
                    .map(|s| Shape::sphere(DVec3::from_array(s.centre), s.radius));
                let capsules = l.capsules.iter().map(|c| {
                    Shape::capsule(DVec3::from_array(c.a), DVec3::from_array(c.b), c.radius)
                });
                Link {
                    name: l.name.clone(),
                    shapes: spheres.chain(capsules).collect(),
                }
            })
            .collect();
        let joints = self
            .joints
            .iter()
            .enumerate()
            .map(|(i, j)| self.joint(i, j))
            .collect::<Result<Vec<_>, _>>()?;
        ArmModel::new(&self.name, base, links, joints)
    }

    fn joint(&self, i: usize, j: &RawJoint) -> Result<Joint, GuardError> {
        for (role, named, at) in [("parent", &j.parent, i), ("child", &j.child, i + 1)] {
            if let (Some(found), Some(link)) = (named, self.links.get(at)) {
                if *found != link.name {
                    return Err(GuardError::ChainMismatch {
                        joint: j.name.clone(),
                        role,
                        expected: link.name.clone(),
                        found: found.clone(),
                    });
                }
            }
        }
        let axis = match (j.kind, j.axis) {
            (JointKind::Fixed, axis) => axis.unwrap_or([0.0, 0.0, 1.0]),
            (_, Some(axis)) => axis,
            (_, None) => {
                return Err(GuardError::Toml(format!(
                    "joint '{}' is {:?} and needs an axis",
                    j.name, j.kind
                )))
            }
        };
        Joint::new(&j.name, j.kind, axis, j.xyz, j.rpy, j.limits)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TWO_LINK: &str = r#"
        name = "two"
        [base]
        xyz = [0, 0, 1]
        [[links]]
        name = "l0"
        [[links]]
        name = "l1"
        spheres = [{ centre = [0, 0, 0.5], radius = 0.1 }]
        capsules = [{ a = [0, 0, 0], b = [0, 0, 1], radius = 0.05 }]
        [[joints]]
        name = "j0"
        kind = "revolute"
        parent = "l0"
        child = "l1"
        axis = [0, 1, 0]
        limits = [-1, 1]
        [trajectory]
        waypoints = [{ positions = [0.5], duration = 1 }, { positions = [-0.5], duration = 2 }]
        [guard]
        stop_distance = 0.1
    "#;

    #[test]
    fn parses_a_small_arm_with_trajectory_and_guard() {
        let file = ArmFile::from_toml_str(TWO_LINK).unwrap();
        assert_eq!(file.arm.name(), "two");
        assert_eq!((file.arm.dof(), file.arm.shape_count()), (1, 2));
        assert!(matches!(file.arm.links()[1].shapes[1], Shape::Capsule(_)));
        let t = file.trajectory.unwrap();
        assert_eq!((t.period(), t.looping()), (3.0, true));
        assert_eq!(file.guard.stop_distance, 0.1);
        assert_eq!(file.guard.max_report, GuardConfig::default().max_report);
        let pose = file.arm.forward(&[0.0]).unwrap();
        let Shape::Sphere(s) = pose.shapes[0].shape else {
            panic!("sphere first")
        };
        assert!((s.centre - DVec3::new(0.0, 0.0, 1.5)).length() < 1e-12);
    }

    #[test]
    fn errors_name_the_problem() {
        let bad = |from: &str, to: &str| ArmModel::from_toml_str(&TWO_LINK.replace(from, to));
        assert!(matches!(
            bad("radius = 0.1", "radius = 0"),
            Err(GuardError::BadRadius { .. })
        ));
        assert!(matches!(
            bad("axis = [0, 1, 0]", "axis = [0, 0, 0]"),
            Err(GuardError::BadAxis { .. })
        ));
        assert!(matches!(
            bad("axis = [0, 1, 0]", ""),
            Err(GuardError::Toml(m)) if m.contains("needs an axis")
        ));
        assert!(matches!(
            bad("parent = \"l0\"", "parent = \"l1\""),
            Err(GuardError::ChainMismatch { role: "parent", .. })
        ));
        assert!(matches!(
            bad("name = \"l1\"", "name = \"l0\""),
            Err(GuardError::DuplicateName { .. }) | Err(GuardError::ChainMismatch { .. })
        ));
        assert!(matches!(
            bad("limits = [-1, 1]", "limits = [1, -1]"),
            Err(GuardError::BadLimits { .. })
        ));
        assert!(matches!(
            bad("positions = [0.5]", "positions = [1.5]"),
            Err(GuardError::OutsideLimits { .. })
        ));
        assert!(matches!(
            bad("duration = 1 ", "duration = -1 "),
            Err(GuardError::BadDuration { .. })
        ));
        assert!(matches!(
            bad("stop_distance = 0.1", "stop_distance = 9.0"),
            Err(GuardError::BadConfig(_))
        ));
        assert!(matches!(
            bad("kind = \"revolute\"", "kind = \"ball\""),
            Err(GuardError::Toml(_))
        ));
        assert!(matches!(
            bad("radius = 0.05", "radius = 0.05, colour = 1"),
            Err(GuardError::Toml(_))
        ));
        assert!(matches!(
            bad("xyz = [0, 0, 1]", "xyz = [0, 0, nan]"),
            Err(GuardError::NonFinite { .. })
        ));
        assert!(matches!(
            bad("[[joints]]", "[[joints_]]"),
            Err(GuardError::Toml(_))
        ));
        assert!(matches!(
            ArmModel::from_toml_str("this is not toml"),
            Err(GuardError::Toml(_))
        ));
    }

    #[test]
    fn link_count_must_match() {
        let text = TWO_LINK.replace("[[links]]\n        name = \"l0\"", "");
        assert!(ArmModel::from_toml_str(&text).is_err());
    }
}
