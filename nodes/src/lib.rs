//! The shroud command line and nodes: thin wrappers that parse arguments, read
//! and write files, move messages over zenoh, call `shroud-core`, and print what
//! happened.

pub mod args;
pub mod bench;
pub mod cli;
pub mod files;
pub mod ingest;
pub mod introspect;
pub mod launch;
pub mod node;
pub mod parse;
pub mod recording;
pub mod to_foxglove;
pub mod transport;
