//! The one interface every CAN frame source offers the CAN reader.

use super::SourceError;
use shroud_core::ingest::can::CanFrame;
use shroud_core::ingest::DecoderStats;
use std::time::Duration;

/// A source of classic CAN frames: a SocketCAN interface, an SLCAN adapter, a
/// candump log replay, or an in-memory bus.
pub trait CanSource: Send {
    /// Waits at most about `timeout` for the next frame. `Ok(None)`: nothing
    /// arrived in time. [`SourceError::Disconnected`]: the device went away (the
    /// reader reopens it). [`SourceError::Finished`]: there will be no more frames.
    fn recv(&mut self, timeout: Duration) -> Result<Option<CanFrame>, SourceError>;

    /// A short name for logs (`socketcan:can0`, `slcan:/dev/ttyACM0`, ...).
    fn name(&self) -> String;

    /// Counters of the transport's own decoding (SLCAN lines, candump lines).
    fn transport_stats(&self) -> DecoderStats {
        DecoderStats::default()
    }
}

impl CanSource for Box<dyn CanSource> {
    fn recv(&mut self, timeout: Duration) -> Result<Option<CanFrame>, SourceError> {
        (**self).recv(timeout)
    }

    fn name(&self) -> String {
        (**self).name()
    }

    fn transport_stats(&self) -> DecoderStats {
        (**self).transport_stats()
    }
}
