//! The one runtime every node runs in: its context (session, topics, metrics,
//! stop flag), its typed inputs ([`Input`], queued; [`Listener`], in zenoh's
//! callback) and outputs ([`Output`]) that decode, encode, apply the topic's
//! QoS and shared memory and count what they receive, drop and publish, its
//! life from start to a bounded shutdown, and its status.

mod arrival;
mod context;
mod input;
mod listener;
mod metrics;
mod output;
mod run;
mod status;
#[cfg(test)]
mod tests;
mod watchdog;

pub use arrival::Arrival;
pub use context::{NodeCommon, NodeContext};
pub use input::Input;
pub use listener::{Listener, OnMessage};
pub use metrics::NodeMetrics;
pub use output::Output;
pub use run::run_node;
