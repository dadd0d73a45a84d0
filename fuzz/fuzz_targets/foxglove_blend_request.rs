//! The fuzzer of src/targets/foxglove_blend_request.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
