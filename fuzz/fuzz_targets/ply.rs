//! The fuzzer of src/targets/ply.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
