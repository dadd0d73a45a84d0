//! The fuzzer of src/targets/slcan.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
