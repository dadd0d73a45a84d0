//! Random frames never panic, and every cloud is consistent.

use super::support::*;
use crate::assembly::MountPose;
use crate::benewake_can::BenewakeCanModel as Model;
use crate::can::CanFrame;
use crate::can_device::CanDeviceDriver;
use proptest::prelude::*;

proptest! {
    #[test]
    fn random_frames_never_panic(
        frames in proptest::collection::vec(
            (prop_oneof![Just(3u32), Just(4), Just(0x0009_0002), 0u32..0x800], any::<bool>(), any::<bool>(),
             proptest::collection::vec(any::<u8>(), 0..=8), 0u64..80),
            0..200),
    ) {
        let mut d = driver(vec![
            sensor("a", Model::Tf03, 3, MountPose::default()),
            sensor("b", Model::TfminiI, 4, MountPose::default()),
            sensor("c", Model::Tf02, 0x0009_0002, MountPose::default()),
        ]);
        let mut out = Vec::new();
        let mut t = 0;
        for (id, extended, remote, data, dt) in frames {
            t += dt;
            let extended = extended || id > 0x7FF;
            let frame = if remote {
                CanFrame::remote(id, extended, data.len() as u8).unwrap()
            } else {
                CanFrame::new(id, extended, &data).unwrap()
            };
            d.receive(&at(frame, t), &mut out);
            d.poll(host(t), &mut out);
        }
        let missing: u64 = d.missing_by_sensor().iter().map(|(_, n)| n).sum();
        prop_assert_eq!(missing, d.stats().errors("missing_reading"));
        for cloud in clouds(&out) {
            let n = cloud.scan.points.len();
            prop_assert!(n <= 3);
            prop_assert!(cloud.scan.channels.iter().all(|c| c.values.len() == n));
            prop_assert!(cloud.scan.points.iter().flatten().all(|v| v.is_finite()));
        }
    }
}
