//! The fuzzer of src/targets/msg_joints.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
