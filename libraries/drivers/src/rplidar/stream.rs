//! The scan stream after its descriptor: which sample format it carries, and
//! the decoder that turns its bytes into samples, losses and restarts for the
//! revolution assembler.

use super::capsule::CapsuleStream;
use super::dense::DenseLayout;
use super::device::{DeviceStats, HostTime};
use super::express::ExpressLayout;
use super::node::NodeDecoder;
use super::protocol::{answer, CAPSULE_LEN, NODE_LEN};
use super::timing::SampleClock;

// Defined in `sample`, below both the decoders that produce them and this
// module that dispatches to those decoders; re-exported here, where they are
// part of the stream's public API.
pub use super::sample::{Sample, StreamEvent};

/// The sample formats decoded here, by answer type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SampleFormat {
    /// 0x81: 5-byte nodes.
    Standard,
    /// 0x82: legacy express capsules.
    Express,
    /// 0x85: dense capsules.
    Dense,
}

impl SampleFormat {
    /// The format of a stream with this answer type, if decoded here.
    pub fn from_answer_type(answer_type: u8) -> Option<Self> {
        match answer_type {
            answer::MEASUREMENT => Some(Self::Standard),
            answer::CAPSULED => Some(Self::Express),
            answer::DENSE_CAPSULED => Some(Self::Dense),
            _ => None,
        }
    }

    pub fn answer_type(self) -> u8 {
        match self {
            Self::Standard => answer::MEASUREMENT,
            Self::Express => answer::CAPSULED,
            Self::Dense => answer::DENSE_CAPSULED,
        }
    }

    /// The answer length the stream's descriptor announces.
    pub fn packet_len(self) -> usize {
        match self {
            Self::Standard => NODE_LEN,
            Self::Express | Self::Dense => CAPSULE_LEN,
        }
    }

    /// Clean samples that must follow a revolution boundary before the
    /// revolution is trusted (`RevolutionAssembler::new`): 8 for standard
    /// nodes, which have no checksum; 0 for checksummed capsules.
    pub fn boundary_confirmation(self) -> usize {
        match self {
            Self::Standard => 8,
            Self::Express | Self::Dense => 0,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Self::Standard => "standard",
            Self::Express => "express",
            Self::Dense => "dense",
        }
    }
}

/// A decoder of one stream's bytes.
#[derive(Debug, Clone)]
pub enum StreamDecoder {
    Standard(NodeDecoder),
    Express(CapsuleStream<ExpressLayout>),
    Dense(CapsuleStream<DenseLayout>),
}

impl StreamDecoder {
    pub fn new(format: SampleFormat, clock: SampleClock) -> Self {
        match format {
            SampleFormat::Standard => Self::Standard(NodeDecoder::new(clock)),
            SampleFormat::Express => Self::Express(CapsuleStream::new(clock)),
            SampleFormat::Dense => Self::Dense(CapsuleStream::new(clock)),
        }
    }

    /// Decodes `bytes` that arrived at `now`, appending to `events`; counts
    /// rejected input in `stats`.
    pub fn feed(
        &mut self,
        bytes: &[u8],
        now: HostTime,
        stats: &mut DeviceStats,
        events: &mut Vec<StreamEvent>,
    ) {
        match self {
            Self::Standard(d) => d.feed(bytes, now, stats, events),
            Self::Express(d) => d.feed(bytes, now, stats, events),
            Self::Dense(d) => d.feed(bytes, now, stats, events),
        }
    }
}
