//! The fuzzer of src/targets/candump.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
