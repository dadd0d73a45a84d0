//! URDF arms (`ArmModel::from_urdf_str`), through shroud's XML reader; a
//! decoded arm poses.

use crate::check::named;
use glam::DAffine3;
use shroud_guard::ArmModel;

pub fn run(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match ArmModel::from_urdf_str(text, DAffine3::IDENTITY) {
        Ok(arm) => crate::arm::poses(&arm),
        Err(e) => named(&e),
    }
}

pub fn seeds() -> Vec<Vec<u8>> {
    let two_links = r#"<?xml version="1.0"?>
<!-- a comment -->
<robot name="two">
  <link name="base">
    <visual><geometry><mesh filename="ignored.stl"/></geometry></visual>
    <collision><origin xyz="0 0 0.05"/><geometry><sphere radius="0.1"/></geometry></collision>
  </link>
  <link name="arm">
    <collision>
      <origin xyz="0 0 0.25" rpy="0 0 0"/>
      <geometry><cylinder radius="0.04" length="0.5"/></geometry>
    </collision>
    <collision><origin xyz="0 0 0.5"/><geometry><box size="0.1 0.2 0.2"/></geometry></collision>
  </link>
  <link name="slide"><collision><geometry><sphere radius="0.02"/></geometry></collision></link>
  <link name="tool"/>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="arm"/>
    <origin xyz="0 0 0.1" rpy="0 0 0"/>
    <axis xyz="0 1 0"/>
    <limit lower="-1.5" upper="1.5" effort="10" velocity="1"/>
  </joint>
  <joint name="extend" type="prismatic">
    <parent link="arm"/><child link="slide"/>
    <axis xyz="0 0 1"/><limit lower="0" upper="0.2"/>
  </joint>
  <joint name="wrist" type="continuous">
    <parent link="slide"/><child link="tool"/>
    <origin xyz="0 0 0.5" rpy="0.1 0.2 0.3"/>
  </joint>
</robot>"#;
    vec![two_links.as_bytes().to_vec()]
}
