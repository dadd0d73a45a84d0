//! The arm where its latest joint state puts it: each link's frame and the
//! collision shapes in the world, grouped by link, for drawing.

use super::error::SceneError;
use glam::{DQuat, DVec3};
use shroud_guard::{ArmModel, Shape, WorldShape};
use shroud_msg::JointStateMessage;

/// One link posed in the world.
#[derive(Debug, Clone, PartialEq)]
pub struct PosedLink {
    pub name: String,
    /// The link frame's origin and orientation in the world.
    pub origin: DVec3,
    pub rotation: DQuat,
}

/// The arm at one joint state: links in chain order and every collision shape
/// in the world with the index of its link.
#[derive(Debug, Clone, PartialEq)]
pub struct PosedArm {
    pub arm: String,
    pub joints_sequence: u64,
    pub links: Vec<PosedLink>,
    pub shapes: Vec<WorldShape>,
}

impl PosedArm {
    /// The spheres as (link index, centre, radius).
    pub fn spheres(&self) -> impl Iterator<Item = (usize, DVec3, f64)> + '_ {
        self.shapes.iter().filter_map(|s| match s.shape {
            Shape::Sphere(sphere) => Some((s.link, sphere.centre, sphere.radius)),
            Shape::Capsule(_) => None,
        })
    }

    /// The capsules as (link index, end a, end b, radius).
    pub fn capsules(&self) -> impl Iterator<Item = (usize, DVec3, DVec3, f64)> + '_ {
        self.shapes.iter().filter_map(|s| match s.shape {
            Shape::Capsule(c) => Some((s.link, c.a, c.b, c.radius)),
            Shape::Sphere(_) => None,
        })
    }
}

/// Poses `model` at `joints`, which must name the arm's actuated joints in
/// chain order (what the arm node publishes and the guard checks).
pub fn pose_arm(model: &ArmModel, joints: &JointStateMessage) -> Result<PosedArm, SceneError> {
    let expected: Vec<&str> = model.actuated_joints().map(|j| j.name()).collect();
    if joints
        .names
        .iter()
        .map(String::as_str)
        .ne(expected.iter().copied())
    {
        return Err(SceneError::JointNames {
            arm: model.name().to_string(),
            found: joints.names.clone(),
            expected: expected.iter().map(|s| s.to_string()).collect(),
        });
    }
    let pose = model.forward(&joints.positions)?;
    let links = model
        .links()
        .iter()
        .zip(&pose.links)
        .map(|(link, frame)| {
            let (_, rotation, origin) = frame.to_scale_rotation_translation();
            PosedLink {
                name: link.name.clone(),
                origin,
                rotation,
            }
        })
        .collect();
    Ok(PosedArm {
        arm: model.name().to_string(),
        joints_sequence: joints.sequence,
        links,
        shapes: pose.shapes,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use shroud_guard::ArmFile;

    const ARM: &str = r#"
name = "two"
[[links]]
name = "base"
spheres = [{ centre = [0.0, 0.0, 0.0], radius = 0.1 }]
[[links]]
name = "tip"
capsules = [{ a = [0.0, 0.0, 0.0], b = [1.0, 0.0, 0.0], radius = 0.05 }]
[[joints]]
name = "pan"
kind = "revolute"
xyz = [0.0, 0.0, 1.0]
axis = [0.0, 0.0, 1.0]
"#;

    fn joints(names: &[&str], q: &[f64]) -> JointStateMessage {
        JointStateMessage::new(
            1,
            9,
            "two",
            names.iter().map(|s| s.to_string()).collect(),
            q.to_vec(),
        )
    }

    #[test]
    fn poses_links_and_shapes_in_the_world() {
        let arm = ArmFile::from_toml_str(ARM).unwrap().arm;
        let posed = pose_arm(&arm, &joints(&["pan"], &[std::f64::consts::FRAC_PI_2])).unwrap();
        assert_eq!(posed.joints_sequence, 9);
        assert_eq!(posed.links.len(), 2);
        assert_eq!(posed.links[1].name, "tip");
        assert!(posed.links[1].origin.distance(DVec3::new(0.0, 0.0, 1.0)) < 1e-12);
        let spheres: Vec<_> = posed.spheres().collect();
        assert_eq!(spheres.len(), 1);
        assert_eq!(spheres[0].0, 0);
        let capsules: Vec<_> = posed.capsules().collect();
        assert_eq!(capsules.len(), 1);
        let (link, a, b, r) = capsules[0];
        assert_eq!((link, r), (1, 0.05));
        assert!(a.distance(DVec3::new(0.0, 0.0, 1.0)) < 1e-12);
        // A quarter turn about z takes the capsule's +x end to +y.
        assert!(b.distance(DVec3::new(0.0, 1.0, 1.0)) < 1e-12);
    }

    #[test]
    fn foreign_joint_names_and_bad_values_are_named_errors() {
        let arm = ArmFile::from_toml_str(ARM).unwrap().arm;
        assert!(matches!(
            pose_arm(&arm, &joints(&["tilt"], &[0.0])),
            Err(SceneError::JointNames { .. })
        ));
        assert!(matches!(
            pose_arm(&arm, &joints(&["pan", "x"], &[0.0, 0.0])),
            Err(SceneError::JointNames { .. })
        ));
        assert!(matches!(
            pose_arm(&arm, &joints(&["pan"], &[f64::INFINITY])),
            Err(SceneError::Pose(_))
        ));
    }
}
