//! The fuzzer of src/targets/msg_status.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
