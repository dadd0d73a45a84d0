//! The fuzzer of src/targets/ros2_joint_state.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
