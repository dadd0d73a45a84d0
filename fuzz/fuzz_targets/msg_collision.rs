//! The fuzzer of src/targets/msg_collision.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
