//! The fuzzer of src/targets/driver_scip.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
