//! The fuzzer of src/targets/dashboard_frame.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
