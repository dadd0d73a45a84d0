//! The fuzzer of src/targets/pcd.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
