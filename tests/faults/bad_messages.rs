//! Bad messages of every topic kind, made from real ones: random bytes,
//! real encodings cut short, and real messages re-encoded with another schema
//! version (and a sequence number in [`BAD_SEQUENCES`], so that anything
//! derived from one would show). Each is checked to be refused by the decoder
//! of its kind before it is sent: a test of the nodes must not rest on a bad
//! message that happens to be valid.

use shroud_msg::{
    BlendCommandMessage, CloudMessage, CollisionMessage, JointStateMessage, MessageError,
    NodeStatusMessage, SmoothPatchesMessage, SurrogateMessage, TopicKind, SCHEMA_VERSION,
};
use shroud_surrogate::SurrogateWire;
use shroud_viewers::describe::describe;

/// Sequence numbers at and above this one mark bad messages.
pub const BAD_SEQUENCES: u64 = 1 << 40;

/// Versions other than the one this build reads of `kind`, cycled through:
/// 0, the previous and next versions, and the largest.
fn other_versions(kind: TopicKind) -> [u16; 4] {
    let current = match kind {
        TopicKind::Joints => JointStateMessage::VERSION,
        TopicKind::Collision => CollisionMessage::VERSION,
        _ => SCHEMA_VERSION,
    };
    [0, current - 1, current + 1, u16::MAX]
}

/// How a bad message is bad.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Badness {
    Garbage,
    Truncated,
    WrongVersion,
}

pub const BADNESS: [Badness; 3] = [Badness::Garbage, Badness::Truncated, Badness::WrongVersion];

/// `count` bad messages of `kind` of each [`Badness`], made from `real`
/// (a valid encoding of that kind), in the order garbage, truncated,
/// wrong version, repeated.
pub fn bad_messages(kind: TopicKind, real: &[u8], count: usize, seed: u64) -> Vec<Vec<u8>> {
    assert!(describe(kind, real).is_ok(), "the original {kind} is valid");
    let mut random = XorShift(seed | 1);
    let mut out = Vec::with_capacity(count * BADNESS.len());
    for i in 0..count {
        for badness in BADNESS {
            let bad = match badness {
                Badness::Garbage => {
                    let len = random.below(512);
                    random.bytes(len)
                }
                // Every cut from the empty message to one byte short.
                Badness::Truncated => real[..real.len() * i / count].to_vec(),
                Badness::WrongVersion => {
                    let versions = other_versions(kind);
                    let version = versions[i % versions.len()];
                    reversioned(kind, real, version, BAD_SEQUENCES + i as u64)
                        .expect("a real message re-encodes")
                }
            };
            assert!(
                describe(kind, &bad).is_err(),
                "a {badness:?} {kind} message must not decode"
            );
            out.push(bad);
        }
    }
    out
}

/// `real` re-encoded with `version` and, where the kind has one, `sequence`.
fn reversioned(
    kind: TopicKind,
    real: &[u8],
    version: u16,
    sequence: u64,
) -> Result<Vec<u8>, MessageError> {
    match kind {
        TopicKind::Cloud => {
            let mut m = CloudMessage::from_bytes(real)?;
            (m.version, m.sequence) = (version, sequence);
            m.to_bytes()
        }
        TopicKind::Surrogate => {
            let (mut m, _) = SurrogateMessage::from_bytes(real)?;
            (m.version, m.source_sequence) = (version, sequence);
            m.to_bytes()
        }
        TopicKind::Joints => {
            let mut m = JointStateMessage::from_bytes(real)?;
            (m.version, m.sequence) = (version, sequence);
            m.to_bytes()
        }
        TopicKind::Collision => {
            let mut m = CollisionMessage::from_bytes(real)?;
            (m.version, m.joints_sequence) = (version, sequence);
            m.to_bytes()
        }
        TopicKind::Status => {
            let mut m = NodeStatusMessage::from_bytes(real)?;
            m.version = version;
            m.to_bytes()
        }
        TopicKind::Smooth => {
            let mut m = SmoothPatchesMessage::from_bytes(real)?;
            (m.version, m.source_sequence) = (version, sequence);
            m.to_bytes()
        }
        TopicKind::Blend => {
            let mut m = BlendCommandMessage::from_bytes(real)?;
            (m.version, m.sequence) = (version, sequence);
            m.to_bytes()
        }
        TopicKind::Alive => panic!("liveliness tokens carry no message"),
    }
}

/// A small deterministic generator for garbage (xorshift64).
struct XorShift(u64);

impl XorShift {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    fn below(&mut self, n: u64) -> usize {
        (self.next() % n) as usize
    }

    fn bytes(&mut self, len: usize) -> Vec<u8> {
        (0..len).map(|_| self.next() as u8).collect()
    }
}
