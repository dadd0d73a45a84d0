//! The posed arm as a `foxglove.SceneUpdate` (one entity per link,
//! `arm/<arm>/<link>`, its spheres and capsules coloured by the link's
//! clearance band, and one entity `arm/<arm>/speed`, a label above the arm
//! saying how fast the verdict lets it move and which link limits it) and
//! its links as `foxglove.FrameTransforms` (each link's frame `<arm>/<link>`
//! in [`WORLD_FRAME`]). Foxglove has no capsule: each is a cylinder between
//! its end centres and a sphere at each end.

use super::geometry::{color, pose, quaternion, timestamp, vector, WORLD_FRAME};
use foxglove::messages::{
    CylinderPrimitive, FrameTransform, FrameTransforms, KeyValuePair, SceneEntity, SceneUpdate,
    SpherePrimitive, TextPrimitive,
};
use glam::{DQuat, DVec3};
use shroud_guard::{ShownVerdict, VerdictWatch};
use shroud_msg::GuardVerdict;
use shroud_viewers::scene::{
    link_bands, ArmSpeed, ClearanceBand, PosedArm, SpeedState, NO_VERDICT_RGBA,
};
use std::collections::BTreeMap;

/// The bands of the verdict `watch` vouches for at `now_ns`; none after a
/// silence or before the first verdict (grey: nothing is known).
pub fn vouched_bands(watch: Option<&VerdictWatch>, now_ns: u64) -> BTreeMap<String, ClearanceBand> {
    watch
        .map(|w| w.shown(now_ns))
        .filter(|shown| shown.verdict != GuardVerdict::NoVerdict)
        .and_then(|shown| shown.message.map(link_bands))
        .unwrap_or_default()
}

/// The arm's speed as the verdict `watch` shows at `now_ns` allows
/// ([`ArmSpeed`]): stopped after a silence or before the first verdict.
pub fn vouched_speed(watch: Option<&VerdictWatch>, now_ns: u64) -> ArmSpeed {
    match watch {
        Some(w) => ArmSpeed::of(&w.shown(now_ns)),
        None => ArmSpeed::of(&ShownVerdict {
            verdict: GuardVerdict::NoVerdict,
            reason: String::new(),
            message: None,
            age_ns: None,
        }),
    }
}

/// Linear RGBA of the speed label: the colour of the clear band at full
/// speed, of the near band when scaled, of the stop band when stopped.
fn speed_rgba(state: SpeedState) -> [f64; 4] {
    let band = match state {
        SpeedState::Full => ClearanceBand::Clear,
        SpeedState::Scaled => ClearanceBand::Near,
        SpeedState::Stopped => ClearanceBand::Stop,
    };
    let [r, g, b, _] = band.rgba();
    [r, g, b, 1.0]
}

/// `arm`'s collision shapes at `stamp_ns`, coloured by `bands` (a link
/// absent from it is [`NO_VERDICT_RGBA`]), and its speed: a label above the
/// arm (entity `arm/<arm>/speed`, text `<arm>: <speed.label()>`, with the
/// scale and limiting link as metadata), and on the link the verdict names
/// as limiting the scale the metadata `limits_speed` (`62 % (S_p 0.840 m)`;
/// `0 % (...)` for a stop that names one).
pub fn arm_scene(
    arm: &PosedArm,
    bands: &BTreeMap<String, ClearanceBand>,
    speed: &ArmSpeed,
    stamp_ns: u64,
) -> SceneUpdate {
    let limiting = speed
        .limiting_link
        .as_deref()
        .filter(|_| speed.state != SpeedState::Full);
    let mut entities: Vec<(SceneEntity, [f64; 4])> = arm
        .links
        .iter()
        .map(|link| {
            let band = bands.get(&link.name);
            let mut metadata: Vec<KeyValuePair> = band
                .map(|b| KeyValuePair {
                    key: "band".into(),
                    value: b.name().into(),
                })
                .into_iter()
                .collect();
            if limiting == Some(link.name.as_str()) {
                let sp = speed
                    .protective_distance
                    .map_or(String::new(), |sp| format!(" (S_p {sp:.3} m)"));
                metadata.push(KeyValuePair {
                    key: "limits_speed".into(),
                    value: format!("{}{sp}", speed.percent()),
                });
            }
            let entity = SceneEntity {
                timestamp: Some(timestamp(stamp_ns)),
                frame_id: WORLD_FRAME.into(),
                id: format!("arm/{}/{}", arm.arm, link.name),
                metadata,
                ..Default::default()
            };
            (entity, band.map_or(NO_VERDICT_RGBA, |b| b.rgba()))
        })
        .collect();
    // Shapes name their link by index into `links` (`shroud-guard`'s PosedArm).
    for (link, centre, radius) in arm.spheres() {
        if let Some((e, rgba)) = entities.get_mut(link) {
            e.spheres.push(sphere(centre, radius, *rgba));
        }
    }
    for (link, a, b, radius) in arm.capsules() {
        if let Some((e, rgba)) = entities.get_mut(link) {
            e.cylinders.push(cylinder(a, b, radius, *rgba));
            e.spheres.push(sphere(a, radius, *rgba));
            e.spheres.push(sphere(b, radius, *rgba));
        }
    }
    let label = speed_label(arm, speed, stamp_ns);
    SceneUpdate {
        deletions: Vec::new(),
        entities: entities.into_iter().map(|(e, _)| e).chain(label).collect(),
    }
}

/// The entity `arm/<arm>/speed`: the speed's label 0.15 m above the arm's
/// highest shape, over its first link's origin, facing the camera at a
/// fixed size on screen. None for an arm without links.
fn speed_label(arm: &PosedArm, speed: &ArmSpeed, stamp_ns: u64) -> Option<SceneEntity> {
    let base = arm.links.first()?.origin;
    let tops = arm
        .spheres()
        .map(|(_, c, r)| c.z + r)
        .chain(arm.capsules().map(|(_, a, b, r)| a.z.max(b.z) + r))
        .chain(arm.links.iter().map(|l| l.origin.z));
    let top = tops.fold(base.z, f64::max);
    let text = TextPrimitive {
        pose: Some(pose(
            DVec3::new(base.x, base.y, top + 0.15),
            DQuat::IDENTITY,
        )),
        billboard: true,
        font_size: 14.0,
        scale_invariant: true,
        color: Some(color(speed_rgba(speed.state))),
        text: format!("{}: {}", arm.arm, speed.label()),
    };
    let pair = |key: &str, value: String| KeyValuePair {
        key: key.into(),
        value,
    };
    let mut metadata = vec![
        pair("speed_scale", speed.scale.to_string()),
        pair("speed", speed.state.name().into()),
    ];
    if let Some(link) = &speed.limiting_link {
        metadata.push(pair("limiting_link", link.clone()));
    }
    if let Some(sp) = speed.protective_distance {
        metadata.push(pair("protective_distance", format!("{sp:.3}")));
    }
    Some(SceneEntity {
        timestamp: Some(timestamp(stamp_ns)),
        frame_id: WORLD_FRAME.into(),
        id: format!("arm/{}/speed", arm.arm),
        metadata,
        texts: vec![text],
        ..Default::default()
    })
}

fn sphere(centre: DVec3, radius: f64, rgba: [f64; 4]) -> SpherePrimitive {
    SpherePrimitive {
        pose: Some(pose(centre, DQuat::IDENTITY)),
        size: Some(vector(DVec3::splat(2.0 * radius))),
        color: Some(color(rgba)),
    }
}

/// A cylinder of `radius` from `a` to `b`: Foxglove's cylinder stands on its
/// local z axis, centred on its pose, `size.z` tall.
fn cylinder(a: DVec3, b: DVec3, radius: f64, rgba: [f64; 4]) -> CylinderPrimitive {
    let axis = b - a;
    let rotation = axis.try_normalize().map_or(DQuat::IDENTITY, |dir| {
        DQuat::from_rotation_arc(DVec3::Z, dir)
    });
    CylinderPrimitive {
        pose: Some(pose((a + b) / 2.0, rotation)),
        size: Some(vector(DVec3::new(
            2.0 * radius,
            2.0 * radius,
            axis.length(),
        ))),
        bottom_scale: 1.0,
        top_scale: 1.0,
        color: Some(color(rgba)),
    }
}

/// Each link's frame, `<arm>/<link>`, in [`WORLD_FRAME`] at `stamp_ns`.
pub fn arm_transforms(arm: &PosedArm, stamp_ns: u64) -> FrameTransforms {
    FrameTransforms {
        transforms: arm
            .links
            .iter()
            .map(|link| FrameTransform {
                timestamp: Some(timestamp(stamp_ns)),
                parent_frame_id: WORLD_FRAME.into(),
                child_frame_id: format!("{}/{}", arm.arm, link.name),
                translation: Some(vector(link.origin)),
                rotation: Some(quaternion(link.rotation)),
            })
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use shroud_guard::ArmFile;
    use shroud_msg::JointStateMessage;
    use shroud_viewers::scene::pose_arm;

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

    fn posed() -> PosedArm {
        let arm = ArmFile::from_toml_str(ARM).unwrap().arm;
        let joints = JointStateMessage::new(1, 2, "two", vec!["pan".into()], vec![0.0]);
        pose_arm(&arm, &joints).unwrap()
    }

    fn rgba(c: &Option<foxglove::messages::Color>) -> [f64; 4] {
        let c = (*c).unwrap();
        [c.r, c.g, c.b, c.a]
    }

    #[test]
    fn a_capsule_is_a_cylinder_between_two_spheres_coloured_by_band() {
        let arm = posed();
        let bands = BTreeMap::from([("tip".to_string(), ClearanceBand::Near)]);
        let update = arm_scene(&arm, &bands, &vouched_speed(None, 0), 3);
        let ids: Vec<&str> = update.entities.iter().map(|e| e.id.as_str()).collect();
        assert_eq!(ids, ["arm/two/base", "arm/two/tip", "arm/two/speed"]);
        let (base, tip) = (&update.entities[0], &update.entities[1]);
        assert_eq!((base.spheres.len(), base.cylinders.len()), (1, 0));
        assert_eq!(rgba(&base.spheres[0].color), NO_VERDICT_RGBA);
        assert!(base.metadata.is_empty());
        assert_eq!((tip.spheres.len(), tip.cylinders.len()), (2, 1));
        assert_eq!(tip.metadata[0].value, "near");
        let cyl = &tip.cylinders[0];
        assert_eq!(rgba(&cyl.color), ClearanceBand::Near.rgba());
        let size = cyl.size.unwrap();
        assert!((size.x - 0.1).abs() < 1e-12 && (size.z - 1.0).abs() < 1e-12);
        // The capsule runs along x at height 1: the cylinder's centre is its
        // middle and its z axis turns onto x.
        let p = cyl.pose.unwrap();
        let centre = p.position.unwrap();
        assert!((centre.x - 0.5).abs() < 1e-12 && (centre.z - 1.0).abs() < 1e-12);
        let q = p.orientation.unwrap();
        let axis = DQuat::from_xyzw(q.x, q.y, q.z, q.w) * DVec3::Z;
        assert!(axis.distance(DVec3::X) < 1e-12);
        let ends: Vec<f64> = tip
            .spheres
            .iter()
            .map(|s| s.pose.unwrap().position.unwrap().x)
            .collect();
        assert_eq!(ends, [0.0, 1.0]);
        assert!((tip.spheres[0].size.unwrap().y - 0.1).abs() < 1e-12);
    }

    #[test]
    fn links_become_frames_in_the_world_and_verdicts_become_bands() {
        let arm = posed();
        let tf = arm_transforms(&arm, 5);
        let children: Vec<&str> = tf
            .transforms
            .iter()
            .map(|t| t.child_frame_id.as_str())
            .collect();
        assert_eq!(children, ["two/base", "two/tip"]);
        assert!(tf
            .transforms
            .iter()
            .all(|t| t.parent_frame_id == WORLD_FRAME));
        assert_eq!(tf.transforms[1].translation.unwrap().z, 1.0);
        let msg =
            crate::to_foxglove::fixtures::collision(&[("base", 0.01, false), ("tip", 1.0, true)]);
        let bands = link_bands(&msg);
        assert_eq!(bands["base"], ClearanceBand::Stop);
        assert_eq!(bands["tip"], ClearanceBand::Unobserved);
    }

    fn metadata(entity: &SceneEntity) -> BTreeMap<&str, &str> {
        entity
            .metadata
            .iter()
            .map(|kv| (kv.key.as_str(), kv.value.as_str()))
            .collect()
    }

    #[test]
    fn the_speed_label_says_the_scale_and_marks_the_limiting_link() {
        let arm = posed();
        let mut watch = VerdictWatch::new(1_000);
        let mut msg =
            crate::to_foxglove::fixtures::collision(&[("base", 1.0, false), ("tip", 0.4, false)]);
        (msg.speed_scale, msg.limiting_link, msg.protective_distance) = (0.625, "tip".into(), 0.84);
        watch.on_verdict(msg, 0);
        let speed = vouched_speed(Some(&watch), 10);
        let update = arm_scene(&arm, &vouched_bands(Some(&watch), 10), &speed, 3);
        let label = update.entities.last().unwrap();
        assert_eq!(label.id, "arm/two/speed");
        let text = &label.texts[0];
        assert_eq!(text.text, "two: 62 % speed, limited by tip (S_p 0.840 m)");
        assert!(text.billboard && text.scale_invariant);
        assert_eq!(rgba(&text.color), speed_rgba(SpeedState::Scaled));
        // Above the highest shape: the tip's capsule at height 1, radius 0.05.
        let at = text.pose.unwrap().position.unwrap();
        assert!((at.z - 1.2).abs() < 1e-12, "{at:?}");
        let meta = metadata(label);
        assert_eq!(meta["speed_scale"], "0.625");
        assert_eq!(meta["speed"], "scaled");
        assert_eq!(meta["limiting_link"], "tip");
        assert_eq!(meta["protective_distance"], "0.840");
        let (base, tip) = (&update.entities[0], &update.entities[1]);
        assert_eq!(metadata(tip)["limits_speed"], "62 % (S_p 0.840 m)");
        assert!(!metadata(base).contains_key("limits_speed"));
        // A silent guard: stopped, in the stop band's colour, naming nothing.
        let silent = vouched_speed(Some(&watch), 5_000);
        let update = arm_scene(&arm, &BTreeMap::new(), &silent, 3);
        let label = update.entities.last().unwrap();
        assert_eq!(label.texts[0].text, "two: stopped (no-verdict)");
        assert_eq!(rgba(&label.texts[0].color), speed_rgba(SpeedState::Stopped));
        assert!(!metadata(label).contains_key("limiting_link"));
        assert!(update
            .entities
            .iter()
            .all(|e| !metadata(e).contains_key("limits_speed")));
    }
}
