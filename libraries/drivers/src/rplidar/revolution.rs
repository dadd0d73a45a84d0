//! Assembles samples into revolutions: one [`Revolution`] per 360°, from the
//! first sample flagged as starting a revolution to the sample before the
//! next one, in measurement order.
//!
//! Only whole revolutions leave: the samples before the first boundary after
//! a (re)start are discarded (counted once as `partial_revolution`); a
//! revolution in which the stream lost bytes or capsules is dropped whole
//! (counted `incomplete_scan`) and the samples up to the next boundary with
//! it; one that grows beyond the ray limit is dropped (counted
//! `oversize_scan`) likewise. Memory is bounded by the limit (two
//! revolutions: the one collected and one awaiting confirmation).
//!
//! Confirmation: standard nodes carry no checksum, so after a lost byte the
//! decoder can read a few misaligned nodes whose S flags are noise before a
//! check bit fails (seen with a byte removed mid-revolution: four fake
//! starts in a row, then the slides). A revolution completed by a boundary
//! is therefore held until `confirm` more samples have arrived with neither
//! a loss nor another boundary; if either comes first, it is dropped
//! (`incomplete_scan`). Capsule streams are checksummed and use
//! `confirm = 0` (delivered at the boundary). Dropped fragments shorter than
//! `confirm` rays are not counted as scans (they are misaligned noise; the
//! bytes that caused them are counted as `resync`).

use super::angle::rep103;
use super::device::{DeviceStats, Ray};
use super::sample::{Sample, StreamEvent};

/// A complete revolution.
#[derive(Debug, Clone, PartialEq)]
pub struct Revolution {
    /// The first ray's time, wall clock ns.
    pub stamp_ns: u64,
    pub rays: Vec<Ray>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    /// Waiting for a boundary. `after_start`: since a (re)start, so the
    /// samples being discarded are the partial first revolution;
    /// `discarded`: some were.
    Waiting {
        after_start: bool,
        discarded: bool,
    },
    Collecting,
}

/// The assembler; bounded by `max_rays`.
#[derive(Debug, Clone)]
pub struct RevolutionAssembler {
    max_rays: usize,
    confirm: usize,
    /// A completed revolution awaiting `confirm_left` more clean samples.
    held: Option<Revolution>,
    confirm_left: usize,
    phase: Phase,
    rays: Vec<Ray>,
    first_ns: u64,
    last_ns: u64,
}

impl RevolutionAssembler {
    /// `confirm`: clean samples that must follow a boundary before the
    /// revolution it completed is delivered (see the module docs).
    pub fn new(max_rays: usize, confirm: usize) -> Self {
        Self {
            max_rays,
            confirm,
            held: None,
            confirm_left: 0,
            phase: Phase::Waiting {
                after_start: true,
                discarded: false,
            },
            rays: Vec::new(),
            first_ns: 0,
            last_ns: 0,
        }
    }

    /// Takes one stream event; returns a revolution it completed.
    pub fn push(&mut self, event: StreamEvent, stats: &mut DeviceStats) -> Option<Revolution> {
        match event {
            StreamEvent::Sample(sample) => self.on_sample(sample, stats),
            StreamEvent::Loss => {
                self.drop_held(stats);
                self.abandon("incomplete_scan", stats);
                None
            }
            StreamEvent::Restart => {
                // A checksummed restart does not cast doubt on a held
                // revolution.
                let held = self.held.take();
                let discarded = match self.phase {
                    Phase::Collecting => {
                        stats.note("partial_revolution");
                        false
                    }
                    Phase::Waiting { discarded, .. } => discarded,
                };
                self.rays.clear();
                self.phase = Phase::Waiting {
                    after_start: true,
                    discarded,
                };
                held
            }
        }
    }

    fn drop_held(&mut self, stats: &mut DeviceStats) {
        if let Some(held) = self.held.take() {
            self.count_dropped(held.rays.len(), "incomplete_scan", stats);
        }
    }

    /// Counts a dropped revolution of `rays` rays. A fragment shorter than
    /// the confirmation window is the noise of misaligned nodes, not a
    /// revolution: its bytes were counted (`resync`), it is not.
    fn count_dropped(&self, rays: usize, kind: &'static str, stats: &mut DeviceStats) {
        if rays >= self.confirm {
            stats.count(kind);
        }
    }

    /// Drops the revolution being collected, counting it as `kind`.
    fn abandon(&mut self, kind: &'static str, stats: &mut DeviceStats) {
        if self.phase == Phase::Collecting {
            self.count_dropped(self.rays.len(), kind, stats);
            self.rays.clear();
            self.phase = Phase::Waiting {
                after_start: false,
                discarded: false,
            };
        }
    }

    fn on_sample(&mut self, sample: Sample, stats: &mut DeviceStats) -> Option<Revolution> {
        match (self.phase, sample.starts_revolution) {
            (Phase::Waiting { after_start, .. }, false) => {
                self.phase = Phase::Waiting {
                    after_start,
                    discarded: true,
                };
                None
            }
            (
                Phase::Waiting {
                    after_start,
                    discarded,
                },
                true,
            ) => {
                if after_start && discarded {
                    stats.note("partial_revolution");
                }
                self.begin(sample);
                None
            }
            (Phase::Collecting, true) => {
                let done = self.finish();
                self.begin(sample);
                if self.held.is_some() {
                    // Two boundaries within the confirmation window: neither
                    // revolution can be trusted.
                    self.drop_held(stats);
                    return None;
                }
                if self.confirm == 0 {
                    return Some(done);
                }
                self.held = Some(done);
                self.confirm_left = self.confirm;
                None
            }
            (Phase::Collecting, false) => {
                if self.rays.len() >= self.max_rays {
                    self.abandon("oversize_scan", stats);
                } else {
                    self.add(sample);
                }
                self.confirm_step()
            }
        }
    }

    /// One clean sample after a held revolution's boundary.
    fn confirm_step(&mut self) -> Option<Revolution> {
        self.held.as_ref()?;
        self.confirm_left = self.confirm_left.saturating_sub(1);
        if self.confirm_left == 0 {
            self.held.take()
        } else {
            None
        }
    }

    fn begin(&mut self, sample: Sample) {
        self.phase = Phase::Collecting;
        self.rays.clear();
        self.first_ns = sample.time_ns;
        self.last_ns = sample.time_ns;
        self.add(sample);
    }

    /// Appends a ray; its time is clamped to be no earlier than the previous
    /// ray's, so offsets are monotone whatever the arrival jitter.
    fn add(&mut self, sample: Sample) {
        self.last_ns = self.last_ns.max(sample.time_ns);
        let offset = self.last_ns - self.first_ns;
        self.rays.push(Ray {
            angle: rep103(sample.heading_q16),
            range: range_m(sample.distance_q2),
            intensity: sample.quality.map(f32::from),
            offset_ns: u32::try_from(offset).unwrap_or(u32::MAX),
        });
    }

    fn finish(&mut self) -> Revolution {
        Revolution {
            stamp_ns: self.first_ns,
            rays: std::mem::take(&mut self.rays),
        }
    }
}

/// Metres from q2 millimetres; 0 (no return) is NaN.
fn range_m(distance_q2: u32) -> f32 {
    if distance_q2 == 0 {
        f32::NAN
    } else {
        (f64::from(distance_q2) / 4000.0) as f32
    }
}
