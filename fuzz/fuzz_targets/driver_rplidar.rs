//! The fuzzer of src/targets/driver_rplidar.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
