//! The fuzzer of src/targets/driver_ars408.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
