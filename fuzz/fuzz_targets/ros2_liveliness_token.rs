//! The fuzzer of src/targets/ros2_liveliness_token.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
