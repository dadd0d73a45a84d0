//! The fuzzer of src/targets/dashboard_command.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
