//! The fuzzer of src/targets/ros2_attachment.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
