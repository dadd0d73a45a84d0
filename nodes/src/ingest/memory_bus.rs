//! An in-memory CAN bus (a channel pair) for tests and in-process simulators.

use super::{CanSource, SourceError};
use shroud_core::ingest::can::CanFrame;
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

/// The receiving end, a [`CanSource`].
#[derive(Debug)]
pub struct MemoryBus(Receiver<CanFrame>);

/// A new bus: its sender and its source.
pub fn memory_bus() -> (MemoryBusSender, MemoryBus) {
    let (tx, rx) = mpsc::channel();
    (MemoryBusSender(tx), MemoryBus(rx))
}

impl CanSource for MemoryBus {
    fn recv(&mut self, timeout: Duration) -> Result<Option<CanFrame>, SourceError> {
        match self.0.recv_timeout(timeout) {
            Ok(frame) => Ok(Some(frame)),
            Err(RecvTimeoutError::Timeout) => Ok(None),
            Err(RecvTimeoutError::Disconnected) => Err(SourceError::Finished(self.name())),
        }
    }

    fn name(&self) -> String {
        "memory-bus".to_owned()
    }
}
