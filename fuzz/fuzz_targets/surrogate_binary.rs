//! The fuzzer of src/targets/surrogate_binary.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
