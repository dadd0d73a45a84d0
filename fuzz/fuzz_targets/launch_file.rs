//! The fuzzer of src/targets/launch_file.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
