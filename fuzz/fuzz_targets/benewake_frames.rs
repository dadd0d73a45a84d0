//! The fuzzer of src/targets/benewake_frames.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
