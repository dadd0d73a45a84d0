//! The fuzzer of src/targets/rplidar_answers.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
