//! The fuzzer of src/targets/driver_benewake.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
