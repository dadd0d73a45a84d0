//! An in-memory CAN bus (a channel pair) for tests and in-process simulators.
//! Frames are dated by the host's clock as they are read.

use super::can_source::received_now;
use super::{CanSource, SourceError};
use shroud_drivers::can::CanFrame;
use shroud_drivers::can_device::TimedFrame;
use std::sync::mpsc::{self, Receiver, RecvTimeoutError, Sender};
use std::time::Duration;

/// The sending end; clone it for several senders. Dropping every sender ends
/// the bus ([`SourceError::Finished`] once the frames in flight are read).
#[derive(Debug, Clone)]
pub struct MemoryBusSender(Sender<CanFrame>);

impl MemoryBusSender {
    /// Sends a frame; false if the receiving source is gone.
    pub fn send(&self, frame: CanFrame) -> bool {
        self.0.send(frame).is_ok()
    }
}

/// The receiving end, a [`CanSource`]; what the reader sends goes to the
/// bus's `outbox` (the devices' side), if it has one.
#[derive(Debug)]
pub struct MemoryBus {
    inbox: Receiver<CanFrame>,
    outbox: Option<Sender<CanFrame>>,
}

/// A new bus: its sender and its (read-only) source.
pub fn memory_bus() -> (MemoryBusSender, MemoryBus) {
    let (tx, rx) = mpsc::channel();
    (
        MemoryBusSender(tx),
        MemoryBus {
            inbox: rx,
            outbox: None,
        },
    )
}

/// A bus both ways: the devices' sender, the receiver of what the reader
/// sends, and the (writable) source.
pub fn memory_bus_duplex() -> (MemoryBusSender, Receiver<CanFrame>, MemoryBus) {
    let (tx, mut bus) = memory_bus();
    let (out_tx, out_rx) = mpsc::channel();
    bus.outbox = Some(out_tx);
    (tx, out_rx, bus)
}

impl CanSource for MemoryBus {
    fn recv(&mut self, timeout: Duration) -> Result<Option<TimedFrame>, SourceError> {
        match self.inbox.recv_timeout(timeout) {
            Ok(frame) => Ok(Some(received_now(frame))),
            Err(RecvTimeoutError::Timeout) => Ok(None),
            Err(RecvTimeoutError::Disconnected) => Err(SourceError::Finished(self.name())),
        }
    }

    fn send(&mut self, frame: &CanFrame) -> Result<(), SourceError> {
        match &self.outbox {
            Some(out) if out.send(*frame).is_ok() => Ok(()),
            _ => Err(SourceError::Finished(self.name())),
        }
    }

    fn writable(&self) -> bool {
        self.outbox.is_some()
    }

    fn name(&self) -> String {
        "memory-bus".to_owned()
    }
}
