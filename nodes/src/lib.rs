//! The shroud command line and nodes: thin wrappers that parse arguments, read
//! and write files, move messages over zenoh, call the library crates (`libraries/`), and print what
//! happened.

pub mod args;
mod arm_file;
pub mod cli;
pub mod exit;
pub mod files;
pub mod ingest;
pub mod introspect;
pub mod launch;
pub mod node;
pub mod parse;
pub mod recording;
pub mod router;
pub mod runtime;
pub mod timing;
pub mod to_foxglove;
pub mod transport;
