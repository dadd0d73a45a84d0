//! The fuzzer of src/targets/arm_file.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
