//! The fuzzer of src/targets/mcap_recording.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
