//! The fuzzer of src/targets/xyz.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
