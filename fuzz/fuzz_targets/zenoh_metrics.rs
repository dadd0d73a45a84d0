//! The fuzzer of src/targets/zenoh_metrics.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
