//! The fuzzer of src/targets/surrogate_json.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
