//! Launch files: the declarative description of a node graph (which nodes, with
//! which arguments, how to restart them) and the restart policy's arithmetic.
//! Parsing and validation are pure; the supervisor that runs the graph lives in
//! `shroud-nodes`.

mod backoff;
mod error;
mod file;

pub use backoff::{Backoff, RestartDecision};
pub use error::LaunchError;
pub use file::{
    LaunchFile, NodeSpec, RestartPolicy, SummarySpec, ZenohSpec, LAUNCHER_FLAGS, LAUNCHER_NAME,
    NODE_KINDS,
};
