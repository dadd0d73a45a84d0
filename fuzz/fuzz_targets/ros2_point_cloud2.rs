//! The fuzzer of src/targets/ros2_point_cloud2.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
