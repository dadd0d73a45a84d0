//! CAN signal databases (Vector DBC): named messages and signals, and the
//! generic codec that turns a [`CanFrame`] into named physical values and back.
//! Parsing is the `can-dbc` crate's; this module checks what it parsed (every
//! signal fits its message, sizes and scalings are sane) and owns the bit
//! layout (Intel and Motorola), sign, scaling, range and multiplexing.
//!
//! shroud ships the DBC files of the devices it drives ([`builtin`]); a user
//! may pass their own for a variant.

mod builtin;
mod database;
mod error;
mod message;
mod signal;
#[cfg(test)]
mod tests;

pub use builtin::{builtin, BUILTIN};
pub use database::{CanDatabase, MAX_DBC_BYTES, MAX_MESSAGES};
pub use error::DbcError;
pub use message::{DecodedMessage, MessageSpec};
pub use signal::{ByteOrder, Multiplex, SignalSpec};
