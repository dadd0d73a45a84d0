//! The fuzzer of src/targets/scip_replies.rs.

#![no_main]

shroud_fuzz::fuzz_binary!();
