//! The fuzzer of src/targets/msg_smooth.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
