//! The fuzzer of src/targets/msg_surrogate.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
