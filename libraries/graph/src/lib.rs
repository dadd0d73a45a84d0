//! The node graph apart from any transport: launch files and their wiring,
//! node kinds and their ports, metric names, and the bounded backlog and
//! pacing policies between a node's inputs and its work. Pure: time is an
//! argument.

pub mod backlog;
pub mod launch;
pub mod metrics;
pub mod pace;
