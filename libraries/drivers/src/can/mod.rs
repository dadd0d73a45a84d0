//! CAN: the plain [`CanFrame`], the CAN range-sensor protocol (`docs/sensor-protocols.md` §2)
//! with its encoder and scan decoder, and the two ways CAN frames travel outside
//! a SocketCAN socket: SLCAN serial adapters ([`slcan`]) and candump logs
//! ([`candump`]).

pub mod candump;
mod decoder;
mod frame;
mod protocol;
pub mod slcan;
#[cfg(test)]
mod tests;

pub use candump::{format_candump_line, parse_candump_line, CandumpParser, CandumpRecord};
pub use decoder::CanScanDecoder;
pub use frame::{CanFrame, MAX_EXTENDED_ID, MAX_STANDARD_ID};
pub use protocol::{scan_checksum, CanMessage, CanSensorConfig, CAN_VERSION, MAX_CAN_POINTS};
pub use slcan::{SlcanDecoder, SlcanMessage};
