//! The shroud command line: thin wrappers that parse arguments, read and write
//! files, call `shroud-core`, and print what happened.

pub mod bench;
pub mod cli;
pub mod files;
pub mod parse;
