//! Each model's golden frame and invalid-reading rules.

use super::support::*;
use crate::assembly::MountPose;
use crate::benewake_can::{BenewakeCanModel as Model, Validity, DEVICE_TIME_MODULUS_MS};
use crate::can::CanFrame;
use crate::can_device::{CanDeviceDriver, CanDriverOutput};
use crate::device::DeviceState;

fn one(model: Model) -> crate::benewake_can::BenewakeCanDriver {
    driver(vec![crate::benewake_can::RangefinderConfig::new(
        "front",
        model,
        MountPose::default(),
    )])
}

#[test]
fn tf03_golden_frame() {
    // 003#E803C8000000: dist 0x03E8 = 1000 cm, strength 0x00C8 = 200 (TF03
    // manual V1.2.2 Table 7: six bytes, little-endian).
    let frame = CanFrame::new(0x003, false, &[0xE8, 0x03, 0xC8, 0x00, 0x00, 0x00]).unwrap();
    let mut d = one(Model::Tf03);
    let out = receive(&mut d, frame, 5);
    assert_eq!(out[0], CanDriverOutput::State(DeviceState::Streaming));
    let c = clouds(&out);
    assert_eq!(c.len(), 1, "one sensor: every reading completes a cycle");
    assert_eq!(c[0].scan.points, vec![[10.0, 0.0, 0.0]]);
    assert_eq!(c[0].scan.intensity.as_deref(), Some(&[200.0f32][..]));
    assert_eq!(channel(&c[0], "strength"), &[200.0]);
    assert_eq!(channel(&c[0], "sensor_index"), &[0.0]);
    assert!(c[0]
        .scan
        .channels
        .iter()
        .all(|ch| ch.name != "device_time_ms"));
    assert_eq!(c[0].scan.stamp_ns, at(frame, 5).stamp_ns);
    assert_eq!(c[0].received, host(5));
}

#[test]
fn tfmini_i_golden_frame_with_its_timestamp() {
    // 003#F401E80310270000: dist 500 cm, strength 1000, timestamp 10000 ms.
    let frame = CanFrame::new(
        0x003,
        false,
        &[0xF4, 0x01, 0xE8, 0x03, 0x10, 0x27, 0x00, 0x00],
    )
    .unwrap();
    let mut d = one(Model::TfminiI);
    let c = clouds(&receive(&mut d, frame, 1));
    assert_eq!(c[0].scan.points, vec![[5.0, 0.0, 0.0]]);
    assert_eq!(channel(&c[0], "strength"), &[1000.0]);
    assert_eq!(channel(&c[0], "device_time_ms"), &[10000.0]);
    // A stamp past 2^24 ms is published modulo 2^24 (exact in f32).
    let late = le_frame(0x003, 500, 1000, Some(DEVICE_TIME_MODULUS_MS + 7));
    let c = clouds(&receive(&mut d, late, 2));
    assert_eq!(channel(&c[0], "device_time_ms"), &[7.0]);
}

#[test]
fn tf02_golden_frame_big_endian_extended() {
    // Extended 0x00090002, 01 2C 00 FA 05 08 00 00: dist 0x012C = 300 cm,
    // strength 0x00FA = 250, exposure 5, reliability 8 (TF02 manual V1.1 Table 5).
    let frame = CanFrame::new(
        0x0009_0002,
        true,
        &[0x01, 0x2C, 0x00, 0xFA, 0x05, 0x08, 0, 0],
    )
    .unwrap();
    let mut d = one(Model::Tf02);
    let c = clouds(&receive(&mut d, frame, 1));
    assert_eq!(c[0].scan.points, vec![[3.0, 0.0, 0.0]]);
    assert_eq!(channel(&c[0], "strength"), &[250.0]);
    // The same bytes on a standard id are another device's.
    let standard = CanFrame::new(0x0002, false, &frame.data).unwrap();
    assert!(clouds(&receive(&mut d, standard, 2)).is_empty());
    assert_eq!(d.stats().notes("other_id"), 1);
}

#[test]
fn invalid_readings_are_counted_by_kind_and_make_no_point() {
    let cases = [
        (Model::Tf03, le_frame(3, 1000, 39, None), "weak_return"),
        (Model::Tf03, le_frame(3, 0, 500, None), "out_of_range"),
        (Model::Tf03, le_frame(3, 18_001, 500, None), "out_of_range"),
        (Model::TfminiI, le_frame(3, 500, 99, Some(1)), "weak_return"),
        (
            Model::TfminiI,
            le_frame(3, 500, 65_535, Some(1)),
            "saturated",
        ),
        (
            Model::TfminiI,
            le_frame(3, 1_201, 500, Some(1)),
            "out_of_range",
        ),
        (Model::Tf02I, le_frame(3, 4_500, 59, Some(1)), "weak_return"),
        (
            Model::Tf02I,
            le_frame(3, 4_001, 500, Some(1)),
            "out_of_range",
        ),
        (
            Model::Tf02,
            tf02_frame(0x0009_0002, 300, 250, 5, 6),
            "unreliable",
        ),
        (
            Model::Tf02,
            tf02_frame(0x0009_0002, 2_200, 250, 5, 7),
            "out_of_range",
        ),
    ];
    for (model, frame, kind) in cases {
        let mut d = one(model);
        let c = clouds(&receive(&mut d, frame, 1));
        assert_eq!(c.len(), 1, "{model:?} {kind}: the cycle still closes");
        assert!(c[0].scan.points.is_empty(), "{model:?} {kind}");
        assert_eq!(d.stats().invalid_readings(kind), 1, "{model:?} {kind}");
        assert_eq!(d.stats().total_errors(), 0);
    }
    // And the edges that are valid.
    assert_eq!(Model::Tf03.verdict(17_999, 40, None), Validity::Valid);
    // 18000 is the TF03's out-of-range code, however strong the return.
    assert_eq!(Model::Tf03.verdict(18_000, 500, None), Validity::OutOfRange);
    assert_eq!(Model::TfminiI.verdict(1_200, 100, None), Validity::Valid);
    assert_eq!(Model::Tf02I.verdict(4_000, 60, None), Validity::Valid);
    assert_eq!(Model::Tf02.verdict(2_199, 0, Some(7)), Validity::Valid);
}

#[test]
fn a_repeated_tfmini_i_timestamp_is_not_a_new_reading() {
    let mut d = one(Model::TfminiI);
    assert_eq!(
        clouds(&receive(&mut d, le_frame(3, 500, 1000, Some(40)), 1)).len(),
        1
    );
    assert!(clouds(&receive(&mut d, le_frame(3, 510, 1000, Some(40)), 2)).is_empty());
    assert_eq!(d.stats().notes("repeated_reading"), 1);
    assert_eq!(
        clouds(&receive(&mut d, le_frame(3, 520, 1000, Some(50)), 3)).len(),
        1
    );
}

#[test]
fn short_and_remote_frames_are_bad() {
    let mut d = one(Model::TfminiI);
    let short = CanFrame::new(3, false, &[0xF4, 0x01, 0xE8, 0x03, 0x10, 0x27]).unwrap();
    assert!(clouds(&receive(&mut d, short, 1)).is_empty());
    assert!(clouds(&receive(&mut d, CanFrame::remote(3, false, 8).unwrap(), 2)).is_empty());
    assert_eq!(d.stats().errors("bad_frame"), 2);
    // The TF03's six bytes are its full frame, five are not.
    let mut d = one(Model::Tf03);
    let five = CanFrame::new(3, false, &[0xE8, 0x03, 0xC8, 0, 0]).unwrap();
    assert!(clouds(&receive(&mut d, five, 1)).is_empty());
    assert_eq!(d.stats().errors("bad_frame"), 1);
}

#[test]
fn model_names_round_trip() {
    for m in Model::ALL {
        assert_eq!(Model::from_name(m.name()), Some(m));
    }
    assert_eq!(Model::from_name("TF03"), Some(Model::Tf03));
    assert_eq!(Model::from_name("tf04"), None);
}
