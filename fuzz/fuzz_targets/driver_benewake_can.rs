//! The fuzzer of src/targets/driver_benewake_can.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
