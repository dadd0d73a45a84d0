//! Serial scan assembly: joins valid frames, in order, into scans. A scan that
//! loses a frame is dropped whole (never published with a hole); the loss is
//! counted once.

use super::header::FrameHeader;
use crate::{DecoderStats, IngestError, Scan};

#[derive(Debug)]
struct Pending {
    scan: Scan,
    frame_count: u16,
    next_index: u16,
    intensity: Vec<f32>,
}

#[derive(Debug, Default)]
enum State {
    #[default]
    Idle,
    Assembling(Pending),
    /// The scan with this sequence is lost: its remaining frames are discarded
    /// quietly (counted in `discarded_frames`).
    Discarding(u32),
}

/// Frames in, scans out.
#[derive(Debug, Default)]
pub struct ScanAssembler {
    state: State,
    max_scan_points: usize,
}

impl ScanAssembler {
    pub fn new(max_scan_points: usize) -> Self {
        Self {
            state: State::Idle,
            max_scan_points,
        }
    }

    /// Adds a frame's decoded points; pushes a completed scan, and/or the error
    /// that dropped a scan, to `out`.
    pub fn push(
        &mut self,
        header: &FrameHeader,
        points: Vec<[f32; 3]>,
        intensity: Vec<f32>,
        stats: &mut DecoderStats,
        out: &mut Vec<Result<Scan, IngestError>>,
    ) {
        let seq = header.sequence;
        match std::mem::take(&mut self.state) {
            State::Discarding(s) if s == seq => {
                stats.discarded_frames += 1;
                self.state = State::Discarding(s);
                return;
            }
            State::Assembling(p) if p.scan.sequence == seq => {
                return self.continue_scan(p, header, points, intensity, stats, out);
            }
            State::Assembling(p) => {
                out.push(Err(stats.count(incomplete(&p, "a new scan started"))))
            }
            State::Idle | State::Discarding(_) => {}
        }
        if header.frame_index != 0 {
            out.push(Err(stats.count(IngestError::MissingFrame {
                sequence: seq,
                expected: 0,
                found: header.frame_index.into(),
            })));
            stats.discarded_frames += 1;
            self.state = State::Discarding(seq);
            return;
        }
        let pending = Pending {
            scan: Scan {
                sequence: seq,
                stamp_ns: header.stamp_ns,
                points: Vec::new(),
                intensity: None,
                channels: Vec::new(),
            },
            frame_count: header.frame_count,
            next_index: 0,
            intensity: Vec::new(),
        };
        self.continue_scan(pending, header, points, intensity, stats, out);
    }

    fn continue_scan(
        &mut self,
        mut p: Pending,
        header: &FrameHeader,
        points: Vec<[f32; 3]>,
        intensity: Vec<f32>,
        stats: &mut DecoderStats,
        out: &mut Vec<Result<Scan, IngestError>>,
    ) {
        let seq = header.sequence;
        let index = header.frame_index;
        let error = if index > p.next_index {
            Some(IngestError::MissingFrame {
                sequence: seq,
                expected: p.next_index.into(),
                found: index.into(),
            })
        } else if index < p.next_index {
            Some(IngestError::OutOfOrder {
                sequence: seq,
                expected: p.next_index.into(),
                found: index.into(),
            })
        } else if header.frame_count != p.frame_count
            || header.stamp_ns != p.scan.stamp_ns
            || (index > 0 && header.intensity != p.scan.intensity.is_some())
        {
            Some(IngestError::Malformed {
                what: "serial scan",
                reason: format!(
                    "frame {index} disagrees with frame 0 on stamp, frame count or intensity"
                ),
            })
        } else if p.scan.points.len() + points.len() > self.max_scan_points {
            Some(IngestError::Oversize {
                what: "points in a scan",
                found: p.scan.points.len() + points.len(),
                limit: self.max_scan_points,
            })
        } else {
            None
        };
        if let Some(error) = error {
            out.push(Err(stats.count(error)));
            stats.discarded_frames += 1;
            self.state = State::Discarding(seq);
            return;
        }
        if index == 0 && header.intensity {
            p.scan.intensity = Some(Vec::new());
        }
        p.scan.points.extend_from_slice(&points);
        p.intensity.extend_from_slice(&intensity);
        p.next_index += 1;
        if p.next_index < p.frame_count {
            self.state = State::Assembling(p);
            return;
        }
        if p.scan.intensity.is_some() {
            p.scan.intensity = Some(p.intensity);
        }
        stats.scans += 1;
        stats.points += p.scan.points.len() as u64;
        out.push(Ok(p.scan));
    }

    /// A frame of scan `sequence` was lost to corruption that is already
    /// counted: drop that scan quietly (and count any other scan in progress as
    /// incomplete, since a new one has started).
    pub fn abandon(
        &mut self,
        sequence: u32,
        stats: &mut DecoderStats,
        out: &mut Vec<Result<Scan, IngestError>>,
    ) {
        match std::mem::take(&mut self.state) {
            State::Assembling(p) if p.scan.sequence != sequence => {
                out.push(Err(stats.count(incomplete(&p, "a new scan started"))))
            }
            _ => {}
        }
        self.state = State::Discarding(sequence);
    }

    /// End of stream: a scan in progress is counted incomplete.
    pub fn finish(&mut self, stats: &mut DecoderStats, out: &mut Vec<Result<Scan, IngestError>>) {
        if let State::Assembling(p) = std::mem::take(&mut self.state) {
            out.push(Err(stats.count(incomplete(&p, "the stream ended"))));
        }
    }
}

fn incomplete(p: &Pending, reason: &'static str) -> IngestError {
    IngestError::IncompleteScan {
        sequence: p.scan.sequence,
        received: p.next_index.into(),
        expected: p.frame_count.into(),
        reason,
    }
}
