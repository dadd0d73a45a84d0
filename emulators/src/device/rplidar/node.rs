//! Encodes one standard scan node (answer type 0x81, 5 bytes):
//! `quality<<2 | !S<<1 | S`, `angle_q6<<1 | C` as u16 LE, `distance_q2` u16
//! LE (`sl_lidar_response_measurement_node_t`; protocol PDF §4 "SCAN").

/// One standard-mode sample, in wire units.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Node {
    /// Clockwise degrees × 64, below 360 × 64.
    pub angle_q6: u16,
    /// Millimetres × 4; 0 = no measurement.
    pub distance_q2: u16,
    /// 0..=63 (6 bits).
    pub quality: u8,
    /// First sample of a new turn.
    pub start: bool,
}

impl Node {
    /// The node's five bytes; `broken` clears the check bit C, which every
    /// valid node has set (`handler_normalnode.cpp` rejects it).
    pub(crate) fn encode(self, broken: bool) -> [u8; 5] {
        let start = u8::from(self.start);
        let sync = (self.quality.min(63) << 2) | ((start ^ 1) << 1) | start;
        let check = u16::from(!broken);
        let [a0, a1] = (((self.angle_q6 & 0x7FFF) << 1) | check).to_le_bytes();
        let [d0, d1] = self.distance_q2.to_le_bytes();
        [sync, a0, a1, d0, d1]
    }
}
