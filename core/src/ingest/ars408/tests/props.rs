//! Random input: arbitrary frames never panic, and a published cloud always
//! has exactly the targets its status announced.

use super::support::*;
use crate::ingest::ars408::{Ars408Config, RadarOutput};
use crate::ingest::can::CanFrame;
use crate::ingest::can_device::{CanDeviceDriver, SensorCloud};
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
