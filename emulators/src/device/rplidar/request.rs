//! Cuts the host's byte stream into RPLIDAR requests: `A5 cmd`, or
//! `A5 cmd size payload checksum` when bit 7 of `cmd` is set, the checksum
//! being the XOR of every byte before it (SDK `sl_lidarprotocol_codec.cpp`,
//! `onEncodeData()`; protocol PDF §2 "Request Packets' Format").

use super::protocol::{HAS_PAYLOAD, REQUEST_SYNC};
use super::rejects::{RejectCounts, RejectKind};

/// A partial request is dropped when its next byte is this late (protocol
/// PDF §2: the device discards a request whose bytes are more than 5 s
/// apart).
const INTER_BYTE_TIMEOUT_S: f64 = 5.0;

/// One complete request with a valid checksum.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Request {
    pub cmd: u8,
    /// Empty for commands without payload; at most 255 bytes (the size
    /// field is one byte).
    pub payload: Vec<u8>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Stage {
    Sync,
    Command,
    Size,
    Payload,
    Checksum,
}

/// The request framing state machine.
#[derive(Debug, Clone)]
pub(crate) struct RequestParser {
    stage: Stage,
    cmd: u8,
    size: usize,
    payload: Vec<u8>,
    xor: u8,
    last_byte_at: f64,
}

impl RequestParser {
    pub(crate) fn new() -> Self {
        Self {
            stage: Stage::Sync,
            cmd: 0,
            size: 0,
            payload: Vec::new(),
            xor: 0,
            last_byte_at: 0.0,
        }
    }

    /// Forgets any partial request.
    pub(crate) fn reset(&mut self) {
        self.stage = Stage::Sync;
        self.payload.clear();
    }

    /// Feeds one byte received at `now`; returns a request when this byte
    /// completes a valid one.
    pub(crate) fn push(
        &mut self,
        byte: u8,
        now: f64,
        rejects: &mut RejectCounts,
    ) -> Option<Request> {
        if self.stage != Stage::Sync && now - self.last_byte_at > INTER_BYTE_TIMEOUT_S {
            rejects.count(RejectKind::RequestTimeout);
            self.reset();
        }
        self.last_byte_at = now;
        match self.stage {
            Stage::Sync => self.on_sync(byte, rejects),
            Stage::Command => self.on_command(byte),
            Stage::Size => self.on_size(byte),
            Stage::Payload => self.on_payload(byte),
            Stage::Checksum => self.on_checksum(byte, rejects),
        }
    }

    fn on_sync(&mut self, byte: u8, rejects: &mut RejectCounts) -> Option<Request> {
        if byte == REQUEST_SYNC {
            self.stage = Stage::Command;
            self.xor = byte;
        } else {
            rejects.count(RejectKind::StrayByte);
        }
        None
    }

    fn on_command(&mut self, byte: u8) -> Option<Request> {
        self.cmd = byte;
        self.xor ^= byte;
        if byte & HAS_PAYLOAD == 0 {
            self.stage = Stage::Sync;
            return Some(Request {
                cmd: byte,
                payload: Vec::new(),
            });
        }
        self.stage = Stage::Size;
        None
    }

    fn on_size(&mut self, byte: u8) -> Option<Request> {
        self.size = usize::from(byte);
        self.xor ^= byte;
        self.payload.clear();
        self.stage = if self.size == 0 {
            Stage::Checksum
        } else {
            Stage::Payload
        };
        None
    }

    fn on_payload(&mut self, byte: u8) -> Option<Request> {
        self.payload.push(byte);
        self.xor ^= byte;
        if self.payload.len() >= self.size {
            self.stage = Stage::Checksum;
        }
        None
    }

    fn on_checksum(&mut self, byte: u8, rejects: &mut RejectCounts) -> Option<Request> {
        self.stage = Stage::Sync;
        if byte != self.xor {
            rejects.count(RejectKind::BadChecksum);
            self.payload.clear();
            return None;
        }
        Some(Request {
            cmd: self.cmd,
            payload: std::mem::take(&mut self.payload),
        })
    }
}
