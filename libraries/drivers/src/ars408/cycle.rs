//! One measurement cycle of the radar, assembled frame by frame: a status
//! frame announces how many targets follow, then come the general frames and
//! the optional quality and extended frames, each section with one frame per
//! target in the same order. A cycle is published only whole; any lost,
//! repeated or undecodable frame drops it (sensors.md §2.2).

use super::layout::{code, Section, ID};
use crate::device::{DeviceStats, HostTime};

/// Clusters per cycle: `NofClustersNear` + `NofClustersFar`, 8 bits each.
pub const MAX_CLUSTERS: usize = 255 + 255;
/// Objects per cycle: `NofObjects`, 8 bits.
pub const MAX_OBJECTS: usize = 255;

/// Whether the radar sends a section of follow-up frames.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Expect {
    Yes,
    No,
    /// No RadarState seen yet: the frames themselves decide (see
    /// [`CycleAssembler`]).
    Unknown,
}

impl Expect {
    pub fn from_flag(flag: Option<bool>) -> Self {
        match flag {
            Some(true) => Self::Yes,
            Some(false) => Self::No,
            None => Self::Unknown,
        }
    }
}

/// How follow-up frames' ids relate to their position.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum IdRule {
    /// Clusters: the general frames carry ids 0, 1, 2, ... in order (modulo
    /// 2^bits of the id signal, so a 510-cluster cycle's 8-bit ids wrap).
    Sequential { modulus: u32 },
    /// Objects: the ids are track ids; the general frames' ids must be
    /// distinct, and the quality and extended frames repeat them in order.
    Tracked,
}

/// Why a cycle was dropped; counted under `incomplete_cycle` plus this.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Loss {
    /// `lost_frame`: a frame is missing, repeated or out of order.
    Lost,
    /// `bad_frame`: a frame of the cycle did not decode.
    Bad,
}

impl Loss {
    pub fn counter(self) -> &'static str {
        match self {
            Self::Lost => "lost_frame",
            Self::Bad => "bad_frame",
        }
    }
}

/// What the status frame announced.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Status {
    pub count: usize,
    pub meas_counter: u32,
    pub stamp_ns: u64,
    pub received: HostTime,
}

/// A cycle whose every frame arrived.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct CompleteCycle {
    pub status: Status,
    pub generals: Vec<[f64; 7]>,
    /// One per general, or empty when the radar sent no quality frames.
    pub qualities: Vec<[f64; 5]>,
    pub extendeds: Vec<[f64; 5]>,
    pub with_quality: bool,
    pub with_extended: bool,
}

#[derive(Debug, Clone, PartialEq)]
struct OpenCycle {
    status: Status,
    ids: Vec<u32>,
    generals: Vec<[f64; 7]>,
    qualities: Vec<[f64; 5]>,
    extendeds: Vec<[f64; 5]>,
    quality: Expect,
    extended: Expect,
}

impl OpenCycle {
    fn count(&self) -> usize {
        self.status.count
    }

    fn section_done(expect: Expect, len: usize, count: usize) -> bool {
        match expect {
            Expect::Yes => len == count,
            Expect::No => true,
            Expect::Unknown => count == 0,
        }
    }

    /// Every announced frame arrived, and no section is still undecided.
    fn complete(&self) -> bool {
        let n = self.count();
        self.generals.len() == n
            && Self::section_done(self.quality, self.qualities.len(), n)
            && Self::section_done(self.extended, self.extendeds.len(), n)
    }

    /// Complete if the undecided sections, which have no frames, are taken
    /// as not sent (the next status arrived, or a RadarState said so).
    fn settle_unknown(&mut self) {
        if self.quality == Expect::Unknown && self.qualities.is_empty() {
            self.quality = Expect::No;
        }
        if self.extended == Expect::Unknown && self.extendeds.is_empty() {
            self.extended = Expect::No;
        }
    }

    fn finish(self) -> CompleteCycle {
        CompleteCycle {
            status: self.status,
            generals: self.generals,
            qualities: self.qualities,
            extendeds: self.extendeds,
            with_quality: self.quality == Expect::Yes,
            with_extended: self.extended == Expect::Yes,
        }
    }

    /// Adds one follow-up frame; `Err` when it breaks the cycle.
    fn push(
        &mut self,
        section: Section,
        id: u32,
        rule: IdRule,
        values: &[f64],
    ) -> Result<(), Loss> {
        let n = self.count();
        let generals_done = self.generals.len() == n;
        match section {
            Section::General => {
                let expected_ok = match rule {
                    Rule::Sequential { modulus } => {
                        let position = self.generals.len() as u64 % u64::from(modulus.max(1));
                        u64::from(id) == position
                    }
                    Rule::Tracked => !self.ids.contains(&id),
                };
                if generals_done
                    || !self.qualities.is_empty()
                    || !self.extendeds.is_empty()
                    || !expected_ok
                {
                    return Err(Loss::Lost);
                }
                self.ids.push(id);
                self.generals.push(first_n(values));
            }
            Section::Quality => {
                if self.quality == Expect::No || !generals_done || !self.extendeds.is_empty() {
                    return Err(Loss::Lost);
                }
                self.quality = Expect::Yes;
                if self.ids.get(self.qualities.len()) != Some(&id) {
                    return Err(Loss::Lost);
                }
                self.qualities.push(first_n(values));
            }
            Section::Extended => {
                if self.quality == Expect::Unknown && self.qualities.is_empty() {
                    self.quality = Expect::No;
                }
                let quality_done = Self::section_done(self.quality, self.qualities.len(), n);
                if self.extended == Expect::No || !generals_done || !quality_done {
                    return Err(Loss::Lost);
                }
                self.extended = Expect::Yes;
                if self.ids.get(self.extendeds.len()) != Some(&id) {
                    return Err(Loss::Lost);
                }
                self.extendeds.push(first_n(values));
            }
        }
        Ok(())
    }
}

use IdRule as Rule;

fn first_n<const N: usize>(values: &[f64]) -> [f64; N] {
    let mut out = [f64::NAN; N];
    for (to, from) in out.iter_mut().zip(values) {
        *to = *from;
    }
    out
}

#[derive(Debug, Clone, PartialEq)]
enum Phase {
    /// Since connect, no status yet: follow-up frames belong to a cycle whose
    /// start we missed (noted `partial_first_cycle`).
    Starting,
    /// Between cycles.
    Idle,
    Open(OpenCycle),
    /// A cycle was dropped: its remaining frames are ignored (noted
    /// `dropped_cycle_frame`) until the next status.
    Discarding,
}

/// Assembles cycles. Whether quality (and, for objects, extended) frames
/// follow is what the last RadarState said (`SendQualityCfg`,
/// `SendExtInfoCfg`), fixed when the cycle opens. Before any RadarState it is
/// inferred from the frames: a quality frame after the generals means the
/// radar sends them; if instead the next status (or a frame of a later
/// section) arrives, or a RadarState arrives saying they are off, the cycle
/// is complete without them. So until the first RadarState (50 ms after the
/// radar starts) a cycle may be published one frame late, never wrongly.
///
/// A complete cycle is held until the next status frame shows that no status
/// was lost in between (its MeasCounter is the held one's plus one): the
/// general and quality frames carry no counter, so a cycle whose frames were
/// lost could otherwise be completed by the next cycle's frames (its status
/// lost too) and published as a piece of that cycle under the wrong stamp.
/// This costs one cycle of latency (72 ms on the ARS408), which the cloud's
/// age includes: it counts from the cycle's first frame.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct CycleAssembler {
    rule: IdRule,
    max_count: usize,
    phase: Phase,
    /// The last complete cycle, waiting for the next status to vouch for it.
    held: Option<CompleteCycle>,
}

/// MeasCounter is 16 bits: it wraps to 0 after 65535.
const MEAS_COUNTER_MODULUS: u32 = 1 << 16;

impl CycleAssembler {
    pub fn new(rule: IdRule, max_count: usize) -> Self {
        Self {
            rule,
            max_count,
            phase: Phase::Starting,
            held: None,
        }
    }

    /// Forgets everything (connect, disconnect); `true` if a cycle was open.
    pub fn reset(&mut self) -> bool {
        let was_open = matches!(self.phase, Phase::Open(_)) || self.held.is_some();
        self.phase = Phase::Starting;
        self.held = None;
        was_open
    }

    /// The next status arrived (`None`: it did not decode): the held cycle
    /// is published if the status follows it, else dropped and counted
    /// (`incomplete_cycle`, `lost_status`).
    fn vouch_for_held(
        &mut self,
        next: Option<u32>,
        stats: &mut DeviceStats,
        done: &mut Vec<CompleteCycle>,
    ) {
        let Some(held) = self.held.take() else {
            return;
        };
        let follows = (held.status.meas_counter + 1) % MEAS_COUNTER_MODULUS;
        if next.is_some_and(|c| c % MEAS_COUNTER_MODULUS == follows) {
            done.push(held);
        } else {
            stats.count("incomplete_cycle");
            stats.count("lost_status");
        }
    }

    /// A status frame: `Ok` what it announced (with the expectations of the
    /// sections), `Err` when it did not decode.
    pub fn status(
        &mut self,
        status: Result<Status, Loss>,
        quality: Expect,
        extended: Expect,
        stats: &mut DeviceStats,
        done: &mut Vec<CompleteCycle>,
    ) {
        self.close_before_next(stats, done);
        let counter = status.as_ref().ok().map(|s| s.meas_counter);
        self.vouch_for_held(counter, stats, done);
        let status = match status {
            Ok(status) if status.count <= self.max_count => status,
            Ok(_) | Err(_) => {
                // The new cycle itself is lost: its count is unusable.
                drop_cycle(Loss::Bad, stats);
                self.phase = Phase::Discarding;
                return;
            }
        };
        let mut open = OpenCycle {
            status,
            ids: Vec::with_capacity(status.count),
            generals: Vec::with_capacity(status.count),
            qualities: Vec::new(),
            extendeds: Vec::new(),
            quality,
            extended,
        };
        if quality == Expect::Yes {
            open.qualities.reserve(status.count);
        }
        if extended == Expect::Yes {
            open.extendeds.reserve(status.count);
        }
        self.phase = Phase::Open(open);
        self.publish_if_complete(done);
    }

    /// A follow-up frame: its values (id first), or `Err` when it did not decode.
    pub fn follow_up(
        &mut self,
        section: Section,
        values: Result<&[f64], Loss>,
        stats: &mut DeviceStats,
        done: &mut Vec<CompleteCycle>,
    ) {
        match &mut self.phase {
            Phase::Starting | Phase::Discarding => {
                // No cycle to drop; a frame that does not decode is still
                // counted as such.
                if let Err(loss) = values {
                    stats.count(loss.counter());
                }
                stats.note(if self.phase == Phase::Starting {
                    "partial_first_cycle"
                } else {
                    "dropped_cycle_frame"
                });
            }
            Phase::Idle if section != Section::General => {
                // Quality or extended frames after a cycle that was complete
                // without them: the radar has just turned them on (as the
                // configuration asks). Nothing published was missing them.
                if let Err(loss) = values {
                    stats.count(loss.counter());
                }
                stats.note("dropped_cycle_frame");
            }
            Phase::Idle => {
                // A general frame after the cycle was complete: more frames
                // than the status announced, or the next status was lost (and
                // the held cycle may hold the next cycle's frames).
                self.held = None;
                drop_cycle(values.err().unwrap_or(Loss::Lost), stats);
                self.phase = Phase::Discarding;
            }
            Phase::Open(open) => {
                let id = match values {
                    Ok(v) => v.get(ID).copied().and_then(code).ok_or(Loss::Bad),
                    Err(loss) => Err(loss),
                };
                let pushed = id.and_then(|id| {
                    let v = values.unwrap_or(&[]);
                    open.push(section, id, self.rule, v)
                });
                if let Err(loss) = pushed {
                    drop_cycle(loss, stats);
                    self.phase = Phase::Discarding;
                    return;
                }
                self.publish_if_complete(done);
            }
        }
    }

    /// A RadarState arrived while the open cycle's sections were undecided:
    /// settle them by what it says.
    pub fn radar_says(&mut self, quality: bool, extended: bool, done: &mut Vec<CompleteCycle>) {
        if let Phase::Open(open) = &mut self.phase {
            if open.quality == Expect::Unknown && open.qualities.is_empty() {
                open.quality = Expect::from_flag(Some(quality));
            }
            if open.extended == Expect::Unknown && open.extendeds.is_empty() {
                open.extended = Expect::from_flag(Some(extended));
            }
        }
        self.publish_if_complete(done);
    }

    /// The next status arrived: an open cycle is complete only if nothing is
    /// missing beyond undecided sections without frames.
    fn close_before_next(&mut self, stats: &mut DeviceStats, done: &mut Vec<CompleteCycle>) {
        if let Phase::Open(open) = &mut self.phase {
            open.settle_unknown();
            if !open.complete() {
                drop_cycle(Loss::Lost, stats);
                self.phase = Phase::Idle;
                return;
            }
            self.publish_if_complete(done);
        }
    }

    /// A complete open cycle is held for the next status to vouch for.
    fn publish_if_complete(&mut self, _done: &mut Vec<CompleteCycle>) {
        if matches!(&self.phase, Phase::Open(open) if open.complete()) {
            if let Phase::Open(open) = std::mem::replace(&mut self.phase, Phase::Idle) {
                self.held = Some(open.finish());
            }
        }
    }
}

fn drop_cycle(loss: Loss, stats: &mut DeviceStats) {
    stats.count("incomplete_cycle");
    stats.count(loss.counter());
}
