//! Random input: arbitrary frames never panic, a published cloud always has
//! exactly the targets its status announced, and of a stream of whole cycles
//! with frames lost at random only the cycles the driver can know are whole
//! are published.

use super::support::*;
use crate::ars408::{Ars408Config, RadarOutput};
use crate::can::CanFrame;
use crate::can_device::{CanDeviceDriver, SensorCloud};
use proptest::collection::vec;
use proptest::prelude::*;
use std::collections::HashMap;

fn consistent(cloud: &SensorCloud) -> bool {
    let n = cloud.scan.points.len();
    cloud.scan.intensity.as_ref().is_some_and(|i| i.len() == n)
        && cloud.scan.channels.iter().all(|c| c.values.len() == n)
        && cloud.scan.points.iter().flatten().all(|v| v.is_finite())
}

fn any_frame() -> impl Strategy<Value = CanFrame> {
    let ids = prop_oneof![
        Just(0x200u32),
        Just(0x201),
        Just(0x600),
        Just(0x701),
        Just(0x702),
        Just(0x60A),
        Just(0x60B),
        Just(0x60C),
        Just(0x60D),
        Just(0x700),
        0u32..0x800,
    ];
    (
        ids,
        any::<bool>(),
        any::<bool>(),
        proptest::collection::vec(any::<u8>(), 0..=8),
    )
        .prop_map(|(id, extended, remote, data)| {
            if remote {
                CanFrame::remote(id, extended, data.len() as u8).unwrap()
            } else {
                CanFrame::new(id, extended, &data).unwrap()
            }
        })
}

/// A step of a plausible radar stream, some of it broken.
#[derive(Debug, Clone)]
enum Step {
    Status(u64),
    General(u64),
    Quality(u64),
    State(bool),
    Silence(u64),
}

fn step() -> impl Strategy<Value = Step> {
    prop_oneof![
        (0u64..6).prop_map(Step::Status),
        (0u64..6).prop_map(Step::General),
        (0u64..6).prop_map(Step::Quality),
        any::<bool>().prop_map(Step::State),
        (0u64..2000).prop_map(Step::Silence),
    ]
}

proptest! {
    #[test]
    fn random_frames_never_panic(
        frames in proptest::collection::vec(any_frame(), 0..200),
        objects in any::<bool>(),
        writable in any::<bool>(),
    ) {
        let output = if objects { RadarOutput::Objects } else { RadarOutput::Clusters };
        let config = Ars408Config { output, ..Ars408Config::default() };
        let (mut d, _) = driver(config);
        let mut out = Vec::new();
        d.connect(host(0), writable, &mut out);
        for (k, f) in frames.iter().enumerate() {
            d.receive(&at(*f, k as u64 * 7), &mut out);
            d.poll(host(k as u64 * 7), &mut out);
        }
        d.disconnect(&mut out);
        for cloud in clouds(&out) {
            prop_assert!(consistent(&cloud));
        }
    }

    #[test]
    fn clouds_have_the_announced_count(steps in proptest::collection::vec(step(), 0..150)) {
        let (mut d, _) = driver(Ars408Config::default());
        let mut announced = HashMap::new();
        let mut counter = 0u64;
        let mut t = 0;
        let mut out = Vec::new();
        // Generals get sequential ids unless the step says otherwise: a
        // `General(k)` with k != 0 skips k - 1 ids (k = 1 is the in-order one).
        let mut next_id = 0;
        for s in steps {
            t += 1;
            let frame = match s {
                Step::Status(n) => {
                    counter += 1;
                    announced.insert(counter as u32, n as usize);
                    next_id = 0;
                    cluster_status(0, n, 0, counter)
                }
                Step::General(k) => {
                    let id = next_id + k.saturating_sub(1);
                    next_id = id + 1;
                    cluster_general(0, General::at(id, 1.0 + id as f64, 0.1))
                }
                Step::Quality(id) => cluster_quality(0, id, 1, 1, 1, 0),
                Step::State(quality) => radar_state(0, State::clusters(quality)),
                Step::Silence(ms) => {
                    t += ms;
                    d.poll(host(t), &mut out);
                    continue;
                }
            };
            d.receive(&at(frame, t), &mut out);
        }
        for cloud in clouds(&out) {
            prop_assert!(consistent(&cloud));
            prop_assert_eq!(Some(&cloud.scan.points.len()), announced.get(&cloud.scan.sequence));
            // Clusters of a published cycle are in id order: x = 1 + id.
            for (k, p) in cloud.scan.points.iter().enumerate() {
                prop_assert!(close(p[0], 1.0 + k as f32));
            }
        }
    }
}

/// Half the DBC's 0.2 m step of DistLong and DistLat: a point decoded from
/// any other raw code than the one sent is off by at least 0.2 m.
const HALF_STEP_M: f64 = 0.1;
/// Targets per generated cycle are below this.
const MAX_TARGETS: usize = 12;
/// Generated cycles are fewer than this.
const MAX_CYCLES: usize = 20;
/// Frames of the longest generated stream: a status, then a general and a
/// quality frame per target, per cycle.
const MAX_FRAMES: usize = (MAX_CYCLES - 1) * (1 + 2 * (MAX_TARGETS - 1));

/// What one frame of a generated stream says.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Part {
    Status {
        count: usize,
    },
    General {
        id: usize,
        long: f64,
        lat: f64,
    },
    Quality {
        id: usize,
        long_rms: u64,
        lat_rms: u64,
    },
}

/// A frame the radar sent, with the cycle (index in the stream) it belongs to.
#[derive(Debug, Clone, Copy)]
struct Sent {
    cycle: usize,
    part: Part,
}

impl Sent {
    /// MeasCounter = cycle + 1; near and far both used (the driver adds them).
    fn frame(&self) -> CanFrame {
        match self.part {
            Part::Status { count } => {
                let far = count / 3;
                cluster_status(0, (count - far) as u64, far as u64, self.cycle as u64 + 1)
            }
            Part::General { id, long, lat } => {
                cluster_general(0, General::at(id as u64, long, lat))
            }
            Part::Quality {
                id,
                long_rms,
                lat_rms,
            } => cluster_quality(0, id as u64, long_rms, lat_rms, 1, 0),
        }
    }
}

/// A cloud as this test compares it: MeasCounter, (long, lat) per point and
/// the (DistLong_rms, DistLat_rms) codes per point (empty without quality).
#[derive(Debug, Clone, PartialEq)]
struct Seen {
    sequence: u32,
    points: Vec<(f64, f64)>,
    rms: Vec<(u64, u64)>,
}

impl Seen {
    fn of(cloud: &SensorCloud, quality: bool) -> Self {
        let rms = if quality {
            let long = channel(cloud, "dist_long_rms");
            let lat = channel(cloud, "dist_lat_rms");
            long.iter()
                .zip(lat)
                .map(|(a, b)| (*a as u64, *b as u64))
                .collect()
        } else {
            Vec::new()
        };
        Self {
            sequence: cloud.scan.sequence,
            points: cloud
                .scan
                .points
                .iter()
                .map(|p| (f64::from(p[0]), f64::from(p[1])))
                .collect(),
            rms,
        }
    }

    /// The cloud of the frames `body` (generals then qualities) under the
    /// status of `cycle`.
    fn from_body(cycle: usize, body: &[Sent]) -> Self {
        let mut seen = Self {
            sequence: cycle as u32 + 1,
            points: Vec::new(),
            rms: Vec::new(),
        };
        for sent in body {
            match sent.part {
                Part::General { long, lat, .. } => seen.points.push((long, lat)),
                Part::Quality {
                    long_rms, lat_rms, ..
                } => seen.rms.push((long_rms, lat_rms)),
                Part::Status { .. } => {}
            }
        }
        seen
    }

    /// Same cycle and values; positions within half a DBC step.
    fn same(&self, other: &Self) -> bool {
        self.sequence == other.sequence
            && self.rms == other.rms
            && self.points.len() == other.points.len()
            && self
                .points
                .iter()
                .zip(&other.points)
                .all(|(a, b)| (a.0 - b.0).abs() < HALF_STEP_M && (a.1 - b.1).abs() < HALF_STEP_M)
    }
}

fn same_all(a: &[Seen], b: &[Seen]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.same(y))
}

/// The frames of whole cycles, in the order the radar sends them (sensors.md
/// §2.2): status, generals with ids 0..n-1, then (with quality) qualities
/// with the same ids. Positions are raw codes (DistLong 13 bits x0.2 -500,
/// DistLat 10 bits x0.2 -102.3) so every one is exactly representable.
fn stream(cycles: &[Vec<(u16, u16)>], quality: bool) -> Vec<Sent> {
    let mut sent = Vec::new();
    for (cycle, targets) in cycles.iter().enumerate() {
        let count = targets.len();
        sent.push(Sent {
            cycle,
            part: Part::Status { count },
        });
        for (id, (long, lat)) in targets.iter().enumerate() {
            let long = f64::from(*long) * 0.2 - 500.0;
            let lat = f64::from(*lat) * 0.2 - 102.3;
            sent.push(Sent {
                cycle,
                part: Part::General { id, long, lat },
            });
        }
        if quality {
            for id in 0..count {
                // Codes that differ between neighbouring cycles and targets,
                // so quality values taken from another cycle show.
                let long_rms = ((7 * cycle + id) % 32) as u64;
                let lat_rms = ((cycle + 3 * id) % 32) as u64;
                sent.push(Sent {
                    cycle,
                    part: Part::Quality {
                        id,
                        long_rms,
                        lat_rms,
                    },
                });
            }
        }
    }
    sent
}

/// What a driver that knows whether quality frames follow (a RadarState said
/// so) must publish and count, from the frames it received alone.
///
/// General and quality frames carry no MeasCounter, only the target id, so
/// all the driver can check is that the frames after a status are, in order,
/// `count` generals with ids 0..count-1 and then, with quality, `count`
/// qualities with the same ids. The cycle is complete the moment that many
/// have arrived (a count of 0 is complete at its status), but it is held, not
/// published, until the next status shows that no status was lost in between
/// (its MeasCounter is the held one's plus one). So, per received status and
/// the frames up to the next received status (its segment):
/// - the segment starts with the whole body and the next received status is
///   the next cycle's: published with the values of those frames; if instead
///   a general follows in the segment (more targets than announced, or a lost
///   status), it is dropped and counted `incomplete_cycle` once; if the next
///   received status skips a MeasCounter (a status was lost), dropped and
///   counted once (`lost_status`); at the end of the stream it stays held,
///   unpublished and uncounted;
/// - a frame of the body's length is not the one due: counted once (the rest
///   of the segment is ignored);
/// - the segment is a proper prefix of the body: counted once when the next
///   status arrives; at the end of the stream it stays open, uncounted.
///
/// Frames before the first received status belong to a cycle whose start was
/// lost: ignored, uncounted.
fn judge(received: &[Sent], quality: bool) -> (Vec<Seen>, u64) {
    let starts: Vec<usize> = received
        .iter()
        .enumerate()
        .filter(|(_, s)| matches!(s.part, Part::Status { .. }))
        .map(|(k, _)| k)
        .collect();
    let mut published = Vec::new();
    let mut incomplete = 0;
    for (k, &start) in starts.iter().enumerate() {
        let Part::Status { count } = received[start].part else {
            continue;
        };
        let next = starts.get(k + 1).copied();
        let segment = &received[start + 1..next.unwrap_or(received.len())];
        let due = count * if quality { 2 } else { 1 };
        let fits = |pos: usize, part: Part| match part {
            Part::General { id, .. } => pos < count && id == pos,
            Part::Quality { id, .. } => quality && pos >= count && id == pos - count,
            Part::Status { .. } => false,
        };
        let matched = segment
            .iter()
            .take(due)
            .enumerate()
            .take_while(|(pos, s)| fits(*pos, s.part))
            .count();
        if matched == due {
            let surplus = segment[due..]
                .iter()
                .any(|s| matches!(s.part, Part::General { .. }));
            let cycle = received[start].cycle;
            match next {
                _ if surplus => incomplete += 1,
                Some(next) if received[next].cycle == cycle + 1 => {
                    published.push(Seen::from_body(cycle, &segment[..due]));
                }
                Some(_) => incomplete += 1,
                None => {}
            }
        } else if matched < segment.len() || next.is_some() {
            incomplete += 1;
        }
    }
    (published, incomplete)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Whole cycles, some frames lost at random (statuses too, sometimes
    /// none): the clouds are exactly what [`judge`] says the driver can know
    /// is whole, which are exactly the cycles that lost nothing and whose
    /// next status arrived, with their own values.
    #[test]
    fn only_cycles_known_whole_are_published(
        cycles in vec(vec((0u16..8192, 0u16..1024), 0..MAX_TARGETS), 1..MAX_CYCLES),
        quality in any::<bool>(),
        // A frame is lost when its draw is below the threshold (0: none).
        threshold in prop_oneof![1 => Just(0u8), 4 => 0u8..160],
        draws in vec(any::<u8>(), MAX_FRAMES),
    ) {
        let sent = stream(&cycles, quality);
        let lost: Vec<bool> = sent
            .iter()
            .zip(draws.iter().chain(std::iter::repeat(&u8::MAX)))
            .map(|(_, draw)| *draw < threshold)
            .collect();
        let received: Vec<Sent> = sent
            .iter()
            .zip(&lost)
            .filter(|(_, lost)| !**lost)
            .map(|(s, _)| *s)
            .collect();
        let frames: Vec<CanFrame> = received.iter().map(Sent::frame).collect();

        let (mut d, _) = driver(Ars408Config::default());
        feed(&mut d, 0, &[radar_state(0, State::clusters(quality))]);
        let seen: Vec<Seen> = clouds(&feed(&mut d, 1, &frames))
            .iter()
            .map(|c| Seen::of(c, quality))
            .collect();
        let incomplete = d.stats().errors("incomplete_cycle");

        // Exactly what the driver can know from what it received.
        let (expected, expected_incomplete) = judge(&received, quality);
        prop_assert!(same_all(&seen, &expected), "seen {:?}\nexpected {:?}", seen, expected);
        prop_assert_eq!(incomplete, expected_incomplete);

        // The same in terms of cycles, independent of `judge`.
        let k = cycles.len();
        let frames_of = |c: usize| -> Vec<usize> {
            (0..sent.len()).filter(|i| sent[*i].cycle == c).collect()
        };
        let status_lost: Vec<bool> = (0..k)
            .map(|c| frames_of(c).first().is_some_and(|i| lost[*i]))
            .collect();
        let lossy: Vec<bool> = (0..k).map(|c| frames_of(c).iter().any(|i| lost[*i])).collect();
        let own = |c: usize| {
            let body: Vec<Sent> = frames_of(c).iter().skip(1).map(|i| sent[*i]).collect();
            Seen::from_body(c, &body)
        };
        // In order, one per cycle at most.
        prop_assert!(seen.windows(2).all(|w| w[0].sequence < w[1].sequence));
        // Every cycle that lost nothing and whose next status arrived, with
        // its own values.
        let vouched = |c: usize| !lossy[c] && c + 1 < k && !status_lost[c + 1];
        for c in (0..k).filter(|c| vouched(*c)) {
            let mine = own(c);
            prop_assert!(seen.iter().any(|s| s.same(&mine)), "cycle {} missing or wrong", c);
        }
        // And no other. A cycle that lost frames and whose next status was
        // lost too could be completed by the next cycle's frames; it is held,
        // and dropped when the status after arrives with a MeasCounter that
        // skips one (or a stray general arrives first, or the stream ends),
        // so no cloud borrows another cycle's frames. The last cycle is
        // never published: no status follows it.
        for s in &seen {
            let c = s.sequence as usize - 1;
            prop_assert!(vouched(c), "cycle {} published though not vouched for", c);
        }
        // With every status received the clouds are exactly the cycles that
        // lost nothing but the last, and `incomplete_cycle` counts every
        // cycle that lost a frame except a last one that lost only its tail:
        // nothing after it closes it (it may only close when its count is
        // reached). No MeasCounter jumps, so no held cycle is dropped for it.
        if !status_lost.contains(&true) {
            let whole: Vec<u32> = (0..k - 1)
                .filter(|c| !lossy[*c])
                .map(|c| c as u32 + 1)
                .collect();
            let published: Vec<u32> = seen.iter().map(|s| s.sequence).collect();
            prop_assert_eq!(published, whole);
            let last = frames_of(k - 1);
            let kept = last.iter().take_while(|i| !lost[**i]).count();
            let tail_only = lossy[k - 1] && last[kept..].iter().all(|i| lost[*i]);
            let lossy_count = lossy.iter().filter(|l| **l).count() as u64;
            prop_assert_eq!(incomplete, lossy_count - u64::from(tail_only));
        }
        // With statuses lost the count is not exact in cycle terms: a
        // status-less cycle's generals are charged to the segment before it
        // (possibly completing a lossy one, then dropped for the stray
        // general or the skipped MeasCounter), and the frames before the
        // first status are uncounted. What holds: a lossy cycle whose own and
        // next status arrived is counted, no segment is counted twice, and
        // every segment closed by a later status is published or counted
        // (only the last may be neither).
        let framed = (0..k.saturating_sub(1))
            .filter(|c| !status_lost[*c] && !status_lost[c + 1] && lossy[*c])
            .count() as u64;
        let started = status_lost.iter().filter(|l| !**l).count() as u64;
        let closed = started.saturating_sub(1);
        let published = seen.len() as u64;
        prop_assert!(framed <= incomplete && incomplete + published <= started);
        prop_assert!(closed <= incomplete + published);
    }
}
