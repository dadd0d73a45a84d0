//! The fuzzer of src/targets/rplidar_scans.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
