//! The one runtime every node runs in: its context (session, topics, metrics,
//! stop flag, publishers with the topic's QoS, a payload writer that honours
//! `--shm`), its life from start to a bounded shutdown, its status and its
//! metrics.

mod context;
mod metrics;
mod run;
mod status;
mod watchdog;

pub use context::{NodeCommon, NodeContext};
pub use metrics::NodeMetrics;
pub use run::run_node;
