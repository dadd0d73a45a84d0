//! The one interface every CAN frame source offers the CAN readers.

use super::backoff::Backoff;
use super::device_port::host_now;
use super::{ReaderError, SourceError};
use shroud_drivers::can::CanFrame;
use shroud_drivers::can_device::{FrameClock, TimedFrame};
use shroud_drivers::DecoderStats;
use std::io;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

/// A source of classic CAN frames: a SocketCAN interface, an SLCAN adapter, a
/// candump log replay, or an in-memory bus.
pub trait CanSource: Send {
    /// Waits at most about `timeout` for the next frame, and dates it (see
    /// [`TimedFrame`]: each source says which clock its `stamp_ns` is on).
    /// `Ok(None)`: nothing arrived in time. [`SourceError::Disconnected`]: the
    /// device went away (the reader reopens it). [`SourceError::Finished`]:
    /// there will be no more frames.
    fn recv(&mut self, timeout: Duration) -> Result<Option<TimedFrame>, SourceError>;

    /// Sends a frame to the bus. A read-only source (a log replay) refuses.
    fn send(&mut self, frame: &CanFrame) -> Result<(), SourceError> {
        let _ = frame;
        Err(SourceError::Disconnected {
            source_name: self.name(),
            error: io::Error::new(io::ErrorKind::Unsupported, "read-only CAN source"),
        })
    }

    /// Whether [`send`](Self::send) can reach a bus.
    fn writable(&self) -> bool {
        false
    }

    /// A short name for logs (`socketcan:can0`, `slcan:/dev/ttyACM0`, ...).
    fn name(&self) -> String;

    /// Counters of the transport's own decoding (SLCAN lines, candump lines).
    fn transport_stats(&self) -> DecoderStats {
        DecoderStats::default()
    }
}

impl CanSource for Box<dyn CanSource> {
    fn recv(&mut self, timeout: Duration) -> Result<Option<TimedFrame>, SourceError> {
        (**self).recv(timeout)
    }

    fn send(&mut self, frame: &CanFrame) -> Result<(), SourceError> {
        (**self).send(frame)
    }

    fn writable(&self) -> bool {
        (**self).writable()
    }

    fn name(&self) -> String {
        (**self).name()
    }

    fn transport_stats(&self) -> DecoderStats {
        (**self).transport_stats()
    }
}

/// `frame` dated by this host's clocks as it is handed over now (sources
/// with no better clock: SLCAN adapters, the in-memory bus).
pub fn received_now(frame: CanFrame) -> TimedFrame {
    let received = host_now();
    TimedFrame {
        frame,
        stamp_ns: received.unix_ns,
        clock: FrameClock::HostReceipt,
        received,
    }
}

/// Opens a source with `open`, retrying failed opens with `backoff` (each
/// counted in `failures`, logged at the first and every power of two, and
/// told to `on_failure` with the count) until one opens. `None`: stopped, or
/// the source has finished for good.
pub(super) fn open_with_backoff(
    open: &mut dyn FnMut() -> Result<Box<dyn CanSource>, SourceError>,
    failures: &mut u64,
    backoff: &mut Backoff,
    stop: &AtomicBool,
    on_failure: &mut dyn FnMut(u64),
) -> Result<Option<Box<dyn CanSource>>, ReaderError> {
    while !stop.load(Ordering::Relaxed) {
        match open() {
            Ok(source) => return Ok(Some(source)),
            Err(SourceError::Fatal(message)) => return Err(SourceError::Fatal(message).into()),
            Err(SourceError::Finished(_)) => return Ok(None),
            Err(error) => {
                *failures += 1;
                if *failures == 1 || failures.is_power_of_two() {
                    tracing::warn!(attempts = *failures, "{error}; retrying");
                }
                on_failure(*failures);
                backoff.wait(stop);
            }
        }
    }
    Ok(None)
}
