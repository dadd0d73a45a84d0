//! The fuzzer of src/targets/msg_blend_command.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
