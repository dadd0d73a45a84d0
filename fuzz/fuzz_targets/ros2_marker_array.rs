//! The fuzzer of src/targets/ros2_marker_array.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
