//! Standard scan (answer type 0x81): 5-byte nodes.
//!
//! Protocol PDF Figure 4-5 and `sl_lidar_response_measurement_node_t`:
//! ```text
//! byte0: quality[7:2] | !S[1] | S[0]     S = 1: first node of a new revolution
//! byte1: angle_q6[6:0] << 1 | C          C (check bit) is always 1
//! byte2: angle_q6[14:7]
//! byte3..4: distance_q2, u16 LE          0 = no valid measurement
//! ```
//! Resynchronisation follows `UnpackerHandler_NormalNode::onData`
//! (`handler_normalnode.cpp`): byte0 is accepted only if its S and !S bits
//! differ, byte1 only if its check bit is set. On a rejected byte the window
//! slides by one byte (the SDK drops byte0 and byte1 together when byte1 is
//! rejected; sliding one byte re-examines byte1 as a byte0, which finds the
//! alignment at least as soon). Each discarded byte is counted as `resync`
//! and reported as a loss.

use super::device::{DeviceStats, HostTime};
use super::protocol::NODE_LEN;
use super::sample::{Sample, StreamEvent};
use super::timing::SampleClock;

/// One decoded node.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Node {
    /// 0..63.
    pub quality: u8,
    pub start: bool,
    /// Degrees in q6.
    pub angle_q6: u16,
    /// Millimetres in q2.
    pub distance_q2: u16,
}

/// Whether `byte` can open a node (S and !S differ).
pub fn valid_first(byte: u8) -> bool {
    ((byte >> 1) ^ byte) & 1 == 1
}

/// Whether `byte` can be a node's second byte (check bit set).
pub fn valid_second(byte: u8) -> bool {
    byte & 1 == 1
}

impl Node {
    /// Decodes five bytes (their first two already validated).
    pub fn parse(bytes: [u8; NODE_LEN]) -> Self {
        let [b0, b1, b2, d0, d1] = bytes;
        Self {
            quality: b0 >> 2,
            start: b0 & 1 == 1,
            angle_q6: u16::from_le_bytes([b1, b2]) >> 1,
            distance_q2: u16::from_le_bytes([d0, d1]),
        }
    }
}

/// The streaming decoder of nodes.
#[derive(Debug, Clone)]
pub struct NodeDecoder {
    clock: SampleClock,
    buf: [u8; NODE_LEN],
    len: usize,
}

impl NodeDecoder {
    pub fn new(clock: SampleClock) -> Self {
        Self {
            clock,
            buf: [0; NODE_LEN],
            len: 0,
        }
    }

    pub fn feed(
        &mut self,
        bytes: &[u8],
        now: HostTime,
        stats: &mut DeviceStats,
        events: &mut Vec<StreamEvent>,
    ) {
        for &byte in bytes {
            if let Some(node) = self.push(byte, stats, events) {
                events.push(StreamEvent::Sample(self.sample(node, now)));
            }
        }
    }

    fn push(
        &mut self,
        byte: u8,
        stats: &mut DeviceStats,
        events: &mut Vec<StreamEvent>,
    ) -> Option<Node> {
        if self.len == 1 && !valid_second(byte) {
            self.slide(stats, events);
        }
        if self.len == 0 && !valid_first(byte) {
            self.slide(stats, events);
            return None;
        }
        let slot = self.buf.get_mut(self.len)?;
        *slot = byte;
        self.len += 1;
        if self.len < NODE_LEN {
            return None;
        }
        self.len = 0;
        Some(Node::parse(self.buf))
    }

    /// Discards the oldest byte of the window: with at most one byte held
    /// when a byte is rejected, that empties it.
    fn slide(&mut self, stats: &mut DeviceStats, events: &mut Vec<StreamEvent>) {
        self.len = 0;
        stats.count("resync");
        events.push(StreamEvent::Loss);
    }

    fn sample(&self, node: Node, now: HostTime) -> Sample {
        Sample {
            heading_q16: i64::from(node.angle_q6) << 10,
            distance_q2: u32::from(node.distance_q2),
            quality: Some(node.quality),
            time_ns: self.clock.sample_time(now.unix_ns, NODE_LEN, 1, 0),
            starts_revolution: node.start,
        }
    }
}
