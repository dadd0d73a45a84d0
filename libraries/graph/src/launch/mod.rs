//! Launch files: the declarative description of a node graph (which nodes of
//! which kinds, their settings, the streams they read and write, how to
//! restart them), its checks and drawings, and the restart policy's
//! arithmetic. Parsing and validation are pure; the supervisor that runs the
//! graph, and the check of each node's settings against its own options, live
//! in `shroud-nodes`.

mod access;
mod backoff;
mod draw;
mod error;
mod file;
mod hosts;
mod kind;
mod load;
mod placement;
mod sectors;
mod wiring;

pub use access::{AccessControl, AclPolicy, AclRule, AclSubject};
pub use backoff::{Backoff, RestartDecision};
pub use draw::{wiring_mermaid, wiring_text};
pub use error::LaunchError;
pub use file::{
    LaunchFile, NodeSpec, RestartPolicy, StreamNames, SummarySpec, ZenohSpec, LAUNCHER_FLAGS,
    LAUNCHER_NAME,
};
pub use hosts::{HostSpec, TlsSpec};
pub use kind::{Direction, FlagStyle, NodeKind, Port};
pub use wiring::{check_graph, Edge, Source, Stream, Wire};
