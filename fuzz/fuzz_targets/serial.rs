//! The fuzzer of src/targets/serial.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
