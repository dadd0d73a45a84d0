//! The fuzzer of src/targets/ros2_messages.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
