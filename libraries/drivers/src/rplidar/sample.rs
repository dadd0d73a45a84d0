//! What every scan decoder ([`node`](super::node), and
//! [`capsule`](super::capsule) for express and dense scans) reports: decoded
//! samples, losses and restarts, in stream order, for the revolution
//! assembler.

/// One decoded measurement.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Clockwise heading from the device's forward axis, degrees in q16.
    pub heading_q16: i64,
    /// Millimetres in q2; 0 = no valid return.
    pub distance_q2: u32,
    /// The device's quality (standard scans only: 0..63).
    pub quality: Option<u8>,
    /// When it was measured (wall clock, ns), from
    /// [`SampleClock`](super::timing::SampleClock).
    pub time_ns: u64,
    /// The first sample of a new revolution.
    pub starts_revolution: bool,
}

/// What a stream decoder reports, in stream order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum StreamEvent {
    Sample(Sample),
    /// Bytes or samples were lost here: the revolution in progress has a hole.
    Loss,
    /// The device restarted its scan (an express capsule with S set): the
    /// revolution in progress is cut short.
    Restart,
}
