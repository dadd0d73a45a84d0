//! The fuzzer of src/targets/urdf.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
