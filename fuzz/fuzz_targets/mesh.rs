//! The fuzzer of src/targets/mesh.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
