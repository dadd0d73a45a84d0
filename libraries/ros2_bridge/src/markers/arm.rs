//! The arm's collision shapes at a joint state as markers (namespace
//! `shroud/arm/<arm>`): a `SPHERE` per sphere, a `CYLINDER` and two
//! `SPHERE`s per capsule (RViz has no capsule), each coloured by its link's
//! clearance band in the guard's verdict for that joint state, grey where
//! no verdict speaks for the link.

use super::{marker, pose_at, rgba};
use glam::{DQuat, DVec3};
use shroud_msg::CollisionMessage;
use shroud_ros2::{Marker, MarkerArray, Vector3};
use shroud_viewers::scene::{link_bands, PosedArm, NO_VERDICT_RGBA};

/// `arm`'s shapes in `frame_id` at `stamp_ns`, coloured by `verdict`.
pub fn arm_markers(
    arm: &PosedArm,
    verdict: Option<&CollisionMessage>,
    frame_id: &str,
    stamp_ns: u64,
) -> MarkerArray {
    let bands = verdict.map(link_bands).unwrap_or_default();
    let colour = |link: usize| {
        let band = arm.links.get(link).and_then(|l| bands.get(&l.name));
        rgba(band.map_or(NO_VERDICT_RGBA, |b| b.rgba()))
    };
    let ns = format!("shroud/arm/{}", arm.arm);
    let mut markers = Vec::new();
    let mut add = |kind: i32, centre: DVec3, rotation: DQuat, scale: DVec3, link: usize| {
        let id = markers.len() as i32;
        let mut m = marker(frame_id, stamp_ns, &ns, id, kind);
        m.pose = pose_at(centre, rotation);
        m.scale = Vector3 {
            x: scale.x,
            y: scale.y,
            z: scale.z,
        };
        m.color = colour(link);
        markers.push(m);
    };
    for (link, centre, radius) in arm.spheres() {
        add(
            Marker::SPHERE,
            centre,
            DQuat::IDENTITY,
            DVec3::splat(2.0 * radius),
            link,
        );
    }
    for (link, a, b, radius) in arm.capsules() {
        let axis = b - a;
        // A cylinder marker stands along its pose's z.
        let rotation = DQuat::from_rotation_arc(DVec3::Z, axis.normalize_or(DVec3::Z));
        let diameter = 2.0 * radius;
        let scale = DVec3::new(diameter, diameter, axis.length());
        add(Marker::CYLINDER, (a + b) / 2.0, rotation, scale, link);
        for end in [a, b] {
            add(
                Marker::SPHERE,
                end,
                DQuat::IDENTITY,
                DVec3::splat(diameter),
                link,
            );
        }
    }
    MarkerArray { markers }
}

#[cfg(test)]
mod tests {
    use super::*;
    use shroud_guard::ArmModel;
    use shroud_msg::{GuardVerdict, JointStateMessage, LinkClearance};
    use shroud_viewers::scene::{pose_arm, ClearanceBand};

    const ARM: &str = r#"
name = "two"
[[links]]
name = "base"
spheres = [{ centre = [0.0, 0.0, 0.0], radius = 0.1 }]
[[links]]
name = "tip"
capsules = [{ a = [0.0, 0.0, 0.0], b = [0.0, 0.0, 0.5], radius = 0.05 }]
[[joints]]
name = "j"
kind = "revolute"
axis = [0.0, 0.0, 1.0]
xyz = [0.0, 0.0, 0.2]
"#;

    #[test]
    fn shapes_are_placed_sized_and_coloured_by_their_links_band() {
        let model = ArmModel::from_toml_str(ARM).unwrap();
        let joints = JointStateMessage::new(1, 1, "two", vec!["j".into()], vec![0.3]);
        let posed = pose_arm(&model, &joints).unwrap();
        let mut verdict = sample_verdict();
        verdict.links = vec![
            LinkClearance {
                link: "base".into(),
                clearance: 0.01,
                unobserved: false,
            },
            LinkClearance {
                link: "tip".into(),
                clearance: 1.0,
                unobserved: false,
            },
        ];
        let array = arm_markers(&posed, Some(&verdict), "world", 5);
        let kinds: Vec<i32> = array.markers.iter().map(|m| m.type_).collect();
        assert_eq!(
            kinds,
            [
                Marker::SPHERE,
                Marker::CYLINDER,
                Marker::SPHERE,
                Marker::SPHERE
            ]
        );
        assert_eq!(array.markers[0].color, rgba(ClearanceBand::Stop.rgba()));
        assert_eq!(array.markers[1].color, rgba(ClearanceBand::Clear.rgba()));
        let cylinder = &array.markers[1];
        assert!((cylinder.scale.z - 0.5).abs() < 1e-12 && (cylinder.scale.x - 0.1).abs() < 1e-12);
        assert!((cylinder.pose.position.z - 0.45).abs() < 1e-12);
        let ids: Vec<i32> = array.markers.iter().map(|m| m.id).collect();
        assert_eq!(ids, [0, 1, 2, 3]);
        let grey = arm_markers(&posed, None, "world", 5);
        assert!(grey
            .markers
            .iter()
            .all(|m| m.color == rgba(NO_VERDICT_RGBA)));
    }

    fn sample_verdict() -> CollisionMessage {
        shroud_msg::sample_collision(GuardVerdict::Clear)
    }
}
