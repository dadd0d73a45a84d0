//! The fuzzer of src/targets/msg_cloud.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
