//! The arms a soundness run poses: shroud's demo arm (its launch file, 50
//! spheres) and a small URDF arm whose cylinders become capsules, both
//! hanging above the scene so that they reach into it.

use super::SoundnessError;
use glam::{DAffine3, DQuat, DVec3};
use rand::Rng;
use shroud_guard::{ArmFile, ArmModel};

/// The demo arm's file, as the launcher loads it (base at z = 1.6, hanging).
const DEMO_ARM: &str = include_str!("../../../launch/arms/demo_arm.toml");

/// A five-joint serial arm with collision cylinders (capsules to the guard)
/// and spheres; link z axes point down the chain. Written for this harness.
pub const URDF_ARM: &str = r#"<?xml version="1.0"?>
<robot name="soundness_urdf_arm">
  <link name="mount">
    <collision><origin xyz="0 0 0.04"/><geometry><sphere radius="0.08"/></geometry></collision>
  </link>
  <link name="turret">
    <collision><origin xyz="0 0 0.06"/><geometry><cylinder radius="0.06" length="0.12"/></geometry></collision>
  </link>
  <link name="boom">
    <collision><origin xyz="0 0 0.25"/><geometry><cylinder radius="0.05" length="0.5"/></geometry></collision>
  </link>
  <link name="stick">
    <collision><origin xyz="0 0 0.2" rpy="0 0 0"/><geometry><cylinder radius="0.04" length="0.4"/></geometry></collision>
    <collision><origin xyz="0 0 0.4"/><geometry><sphere radius="0.05"/></geometry></collision>
  </link>
  <link name="wrist">
    <collision><origin xyz="0 0 0.08"/><geometry><cylinder radius="0.035" length="0.16"/></geometry></collision>
  </link>
  <link name="tool">
    <collision><origin xyz="0.03 0 0.06" rpy="0 0.5 0"/><geometry><cylinder radius="0.02" length="0.12"/></geometry></collision>
    <collision><origin xyz="-0.03 0 0.06" rpy="0 -0.5 0"/><geometry><cylinder radius="0.02" length="0.12"/></geometry></collision>
  </link>
  <joint name="slew" type="continuous">
    <parent link="mount"/><child link="turret"/>
    <origin xyz="0 0 0.08"/><axis xyz="0 0 1"/>
  </joint>
  <joint name="lift" type="revolute">
    <parent link="turret"/><child link="boom"/>
    <origin xyz="0 0 0.12"/><axis xyz="0 1 0"/>
    <limit lower="-1.8" upper="1.8" effort="50" velocity="1"/>
  </joint>
  <joint name="reach" type="revolute">
    <parent link="boom"/><child link="stick"/>
    <origin xyz="0 0 0.5"/><axis xyz="0 1 0"/>
    <limit lower="-2.4" upper="2.4" effort="30" velocity="1"/>
  </joint>
  <joint name="pitch" type="revolute">
    <parent link="stick"/><child link="wrist"/>
    <origin xyz="0 0 0.45"/><axis xyz="1 0 0"/>
    <limit lower="-1.6" upper="1.6" effort="10" velocity="2"/>
  </joint>
  <joint name="roll" type="revolute">
    <parent link="wrist"/><child link="tool"/>
    <origin xyz="0 0 0.16"/><axis xyz="0 0 1"/>
    <limit lower="-3.0" upper="3.0" effort="5" velocity="3"/>
  </joint>
</robot>
"#;

/// Which arm a scene poses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ArmKind {
    Demo,
    Urdf,
}

/// Both arms, parsed once per run.
#[derive(Debug, Clone)]
pub struct Arms {
    pub demo: ArmModel,
    pub urdf: ArmModel,
}

impl Arms {
    pub fn load() -> Result<Self, SoundnessError> {
        let demo = ArmFile::from_toml_str(DEMO_ARM)?.arm;
        // Flipped like the demo arm's mount, a little off its axis and higher.
        let base = DAffine3::from_rotation_translation(
            DQuat::from_rotation_x(std::f64::consts::PI),
            DVec3::new(0.15, -0.1, 1.7),
        );
        let urdf = ArmModel::from_urdf_str(URDF_ARM, base)?;
        Ok(Self { demo, urdf })
    }

    pub fn get(&self, kind: ArmKind) -> &ArmModel {
        match kind {
            ArmKind::Demo => &self.demo,
            ArmKind::Urdf => &self.urdf,
        }
    }
}

/// Joint values drawn uniformly within the arm's limits (a full turn either
/// way for a joint without limits).
pub fn random_configuration(arm: &ArmModel, rng: &mut impl Rng) -> Vec<f64> {
    use std::f64::consts::PI;
    arm.actuated_joints()
        .map(|j| match j.limits() {
            Some(l) if l.upper > l.lower => rng.random_range(l.lower..=l.upper),
            Some(l) => l.lower,
            None => rng.random_range(-PI..=PI),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use shroud_guard::Shape;

    #[test]
    fn both_arms_load_and_random_poses_respect_limits() {
        let arms = Arms::load().expect("the arms parse");
        assert_eq!(arms.demo.shape_count(), 50);
        let mut rng = rand_pcg::Pcg64::seed_from_u64(3);
        for kind in [ArmKind::Demo, ArmKind::Urdf] {
            let arm = arms.get(kind);
            for _ in 0..100 {
                let q = random_configuration(arm, &mut rng);
                assert!(arm.check_limits(&q).is_ok());
                assert!(arm.forward(&q).is_ok());
            }
        }
        let pose = arms.urdf.forward(&[0.0; 5]).expect("pose");
        let capsules = pose
            .shapes
            .iter()
            .filter(|s| matches!(s.shape, Shape::Capsule(_)))
            .count();
        assert_eq!(capsules, 6);
    }
}
