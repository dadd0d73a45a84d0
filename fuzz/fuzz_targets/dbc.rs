//! The fuzzer of src/targets/dbc.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
