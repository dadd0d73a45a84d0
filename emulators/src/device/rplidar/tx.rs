//! The device's transmit buffer: bytes sent but not yet collected by a
//! poll, bounded so that a host that never polls cannot grow memory.

use std::collections::VecDeque;

use super::rejects::{RejectCounts, RejectKind};

/// Bytes held between polls: over five seconds of a 115200-baud line.
pub(crate) const TX_CAPACITY: usize = 64 * 1024;

#[derive(Debug, Clone, Default)]
pub(crate) struct TxBuffer {
    bytes: VecDeque<u8>,
}

impl TxBuffer {
    /// Queues `bytes`; what does not fit is dropped and counted.
    pub(crate) fn send(&mut self, bytes: &[u8], rejects: &mut RejectCounts) {
        let room = TX_CAPACITY.saturating_sub(self.bytes.len());
        let (fits, dropped) = bytes.split_at(bytes.len().min(room));
        self.bytes.extend(fits);
        if !dropped.is_empty() {
            let n = u64::try_from(dropped.len()).unwrap_or(u64::MAX);
            rejects.add(RejectKind::TxOverflow, n);
        }
    }

    /// Moves every queued byte to `out`.
    pub(crate) fn drain_into(&mut self, out: &mut Vec<u8>) {
        out.extend(self.bytes.drain(..));
    }
}
