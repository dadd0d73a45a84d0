//! The one runtime every node runs in: its context (session, topics, metrics,
//! stop flag, publishers with the topic's QoS, a payload writer that honours
//! `--shm`), its life from start to a bounded shutdown, and its status.

mod context;
mod run;
mod status;
mod watchdog;

pub use context::{NodeCommon, NodeContext};
pub use run::run_node;
