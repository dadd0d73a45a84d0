//! zenoh transport: session configuration from the command line, the bounded
//! drop-oldest mailbox between a subscriber and its worker, and publishing
//! through shared memory when it is available.

mod args;
mod clock;
mod mailbox;
mod publish;
mod signal;

pub use args::{OnOff, ZenohArgs};
pub use clock::{monotonic_ns, unix_ns};
pub use mailbox::Mailbox;
pub use publish::PayloadWriter;
pub use signal::shutdown_signal;
