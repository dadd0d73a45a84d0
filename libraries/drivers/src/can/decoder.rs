//! CAN scan assembly: START, STAMP, POINT 0..n, END from one sensor's frames ->
//! scans. Frames are numbered START = 0, STAMP = 1, POINT k = k + 2,
//! END = n + 2; a gap is a missing frame, a step back is out of order, and either
//! drops the scan (counted once; its remaining frames are discarded quietly).

use super::frame::CanFrame;
use super::protocol::{point_of, CanMessage, CanSensorConfig, CAN_VERSION};
use crate::{DecoderStats, IngestError, Scan};

#[derive(Debug)]
struct Collecting {
    sequence: u16,
    count: u16,
    stamp_ns: u64,
    next_frame: u32,
    points: Vec<[f32; 3]>,
    hasher: crc32fast::Hasher,
}

#[derive(Debug, Default)]
enum State {
    #[default]
    Idle,
    Collecting(Collecting),
    /// A scan (of this sequence, if known) was lost; frames up to the next
    /// START are discarded.
    Lost(Option<u16>),
}

/// Assembles one sensor's scans from CAN frames (any other id is counted as
/// [`IngestError::UnknownId`] and otherwise ignored).
#[derive(Debug, Default)]
pub struct CanScanDecoder {
    config: CanSensorConfig,
    state: State,
    stats: DecoderStats,
    /// Sequence of the last START seen, to name the scan an orphan frame belongs to.
    last_sequence: Option<u16>,
}

impl CanScanDecoder {
    pub fn new(config: CanSensorConfig) -> Self {
        Self {
            config,
            ..Self::default()
        }
    }

    pub fn config(&self) -> &CanSensorConfig {
        &self.config
    }

    pub fn stats(&self) -> &DecoderStats {
        &self.stats
    }

    /// Feeds one frame; returns a completed scan and/or the errors it caused.
    pub fn push(&mut self, frame: &CanFrame) -> Vec<Result<Scan, IngestError>> {
        self.stats.input += 1;
        let mut out = Vec::new();
        let Some(message) = self.config.classify(frame) else {
            out.push(Err(self.stats.count(IngestError::UnknownId {
                id: frame.id,
                extended: frame.extended,
            })));
            return out;
        };
        if frame.len != 8 {
            if let State::Collecting(c) = &self.state {
                self.state = State::Lost(Some(c.sequence));
            }
            out.push(Err(self.stats.count(IngestError::Malformed {
                what: "CAN sensor frame",
                reason: format!("{message:?} frame with {} data bytes, not 8", frame.len),
            })));
            return out;
        }
        self.stats.frames += 1;
        let d = &frame.data;
        let u16_at = |i: usize| u16::from_le_bytes([d[i], d[i + 1]]);
        if message == CanMessage::Start {
            self.lose(&mut out);
            let sequence = u16_at(0);
            self.last_sequence = Some(sequence);
            if d[4] != CAN_VERSION {
                self.state = State::Lost(Some(sequence));
                out.push(Err(self.stats.count(IngestError::Version {
                    found: d[4],
                    expected: CAN_VERSION,
                })));
                return out;
            }
            let mut hasher = crc32fast::Hasher::new();
            hasher.update(d);
            let count = u16_at(2);
            self.state = State::Collecting(Collecting {
                sequence,
                count,
                stamp_ns: 0,
                next_frame: 1,
                points: Vec::with_capacity(usize::from(count).min(4096)),
                hasher,
            });
            return out;
        }
        let mut c = match std::mem::take(&mut self.state) {
            State::Collecting(c) => c,
            State::Lost(lost) => {
                self.stats.discarded_frames += 1;
                if message != CanMessage::End {
                    self.state = State::Lost(lost);
                } else if lost.is_some_and(|s| s != u16_at(0)) {
                    // The END of another scan: that one lost its START too.
                    out.push(Err(self.stats.count(IngestError::MissingFrame {
                        sequence: u16_at(0).into(),
                        expected: 0,
                        found: u32::from(u16_at(2)) + 2,
                    })));
                }
                return out;
            }
            State::Idle => {
                // A frame of a scan whose START was lost.
                let sequence = match message {
                    CanMessage::End => u16_at(0),
                    _ => self.last_sequence.map_or(0, |s| s.wrapping_add(1)),
                };
                let found = match message {
                    CanMessage::Stamp => 1,
                    CanMessage::Point => u32::from(u16_at(6)) + 2,
                    _ => u32::from(u16_at(2)) + 2,
                };
                self.stats.discarded_frames += 1;
                if message != CanMessage::End {
                    self.state = State::Lost(None);
                }
                out.push(Err(self.stats.count(IngestError::MissingFrame {
                    sequence: sequence.into(),
                    expected: 0,
                    found,
                })));
                return out;
            }
        };
        let number = match message {
            CanMessage::Stamp => 1,
            CanMessage::Point => u32::from(u16_at(6)) + 2,
            _ => u32::from(c.count) + 2,
        };
        let sequence = u32::from(c.sequence);
        let error = if message == CanMessage::End && u16_at(0) != c.sequence {
            Some(IngestError::IncompleteScan {
                sequence,
                received: c.next_frame,
                expected: u32::from(c.count) + 3,
                reason: "the end frame of another scan arrived",
            })
        } else if message == CanMessage::End && u16_at(2) != c.count {
            Some(IngestError::Malformed {
                what: "CAN scan",
                reason: format!(
                    "end frame counts {} points, start frame {}",
                    u16_at(2),
                    c.count
                ),
            })
        } else if message == CanMessage::Point && u32::from(u16_at(6)) >= u32::from(c.count) {
            Some(IngestError::Malformed {
                what: "CAN scan",
                reason: format!("point index {} of a {}-point scan", u16_at(6), c.count),
            })
        } else if number > c.next_frame {
            Some(IngestError::MissingFrame {
                sequence,
                expected: c.next_frame,
                found: number,
            })
        } else if number < c.next_frame {
            Some(IngestError::OutOfOrder {
                sequence,
                expected: c.next_frame,
                found: number,
            })
        } else {
            None
        };
        if let Some(error) = error {
            self.stats.discarded_frames += 1;
            if message != CanMessage::End {
                self.state = State::Lost(Some(c.sequence));
            }
            out.push(Err(self.stats.count(error)));
            return out;
        }
        c.next_frame += 1;
        match message {
            CanMessage::Stamp => {
                c.stamp_ns = u64::from_le_bytes(*d);
                c.hasher.update(d);
            }
            CanMessage::Point => {
                c.points.push(point_of(d).0);
                c.hasher.update(d);
            }
            _ => {
                let found = u32::from_le_bytes([d[4], d[5], d[6], d[7]]);
                let computed = c.hasher.finalize();
                if found != computed {
                    out.push(Err(self.stats.count(IngestError::BadChecksum {
                        sequence,
                        found,
                        computed,
                    })));
                    return out;
                }
                self.stats.scans += 1;
                self.stats.points += c.points.len() as u64;
                out.push(Ok(Scan::new(sequence, c.stamp_ns, c.points)));
                return out;
            }
        }
        self.state = State::Collecting(c);
        out
    }

    /// End of stream: a scan in progress is counted incomplete.
    pub fn finish(&mut self) -> Vec<Result<Scan, IngestError>> {
        let mut out = Vec::new();
        if let State::Collecting(c) = std::mem::take(&mut self.state) {
            out.push(Err(self.stats.count(incomplete(&c, "the stream ended"))));
        }
        out
    }

    /// A new START ends any scan in progress.
    fn lose(&mut self, out: &mut Vec<Result<Scan, IngestError>>) {
        if let State::Collecting(c) = std::mem::take(&mut self.state) {
            out.push(Err(self.stats.count(incomplete(&c, "a new scan started"))));
        }
    }
}

fn incomplete(c: &Collecting, reason: &'static str) -> IngestError {
    IngestError::IncompleteScan {
        sequence: c.sequence.into(),
        received: c.next_frame,
        expected: u32::from(c.count) + 3,
        reason,
    }
}
