//! The fuzzer of src/targets/quad_obj.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
