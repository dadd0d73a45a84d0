//! The fuzzer of src/targets/can_scan.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
