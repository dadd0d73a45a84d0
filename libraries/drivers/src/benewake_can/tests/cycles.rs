//! Several rangefinders on one bus: one cloud per cycle, closed by
//! completion, by a sensor reporting twice, or by the timeout.

use super::support::*;
use crate::assembly::MountPose;
use crate::benewake_can::{
    BenewakeCanConfig, BenewakeCanDriver, BenewakeCanError, BenewakeCanModel as Model,
};
use crate::can_device::{CanDeviceDriver, CanDriverOutput};
use crate::device::DeviceState;
use std::f64::consts::FRAC_PI_2;

/// front: TF03 on 0x003 at (0.5, 0, 0.2) looking forward; left: TFmini-i on
/// 0x004 at (0, 0.3, 0) yawed +90°; rear: TF02 on extended 0x00090002 at
/// (-0.4, 0, 0) yawed 180°.
fn three() -> BenewakeCanDriver {
    driver(vec![
        sensor(
            "front",
            Model::Tf03,
            0x003,
            MountPose::from_xyz_rpy([0.5, 0.0, 0.2], [0.0; 3]),
        ),
        sensor(
            "left",
            Model::TfminiI,
            0x004,
            MountPose::from_xyz_rpy([0.0, 0.3, 0.0], [0.0, 0.0, FRAC_PI_2]),
        ),
        sensor(
            "rear",
            Model::Tf02,
            0x0009_0002,
            MountPose::from_xyz_rpy([-0.4, 0.0, 0.0], [0.0, 0.0, std::f64::consts::PI]),
        ),
    ])
}

fn assert_point(p: [f32; 3], want: [f32; 3]) {
    assert!(
        p.iter().zip(want).all(|(a, b)| close(*a, b)),
        "{p:?} != {want:?}"
    );
}

#[test]
fn three_sensors_make_one_cloud_per_cycle() {
    let mut d = three();
    let mut out = Vec::new();
    for cycle in 0..2u64 {
        let t = 10 * cycle;
        out.extend(receive(&mut d, le_frame(0x003, 200, 500, None), t + 1));
        out.extend(receive(
            &mut d,
            le_frame(0x004, 150, 500, Some(t as u32)),
            t + 2,
        ));
        assert!(clouds(&out).len() == cycle as usize, "not before the third");
        out.extend(receive(
            &mut d,
            tf02_frame(0x0009_0002, 100, 300, 3, 8),
            t + 3,
        ));
    }
    let c = clouds(&out);
    assert_eq!(c.len(), 2);
    for (k, cloud) in c.iter().enumerate() {
        assert_eq!(cloud.scan.sequence, k as u32);
        assert_eq!(cloud.scan.points.len(), 3);
        // front: 2 m ahead of (0.5, 0, 0.2); left: 1.5 m along +y from (0, 0.3, 0);
        // rear: 1 m along -x from (-0.4, 0, 0).
        assert_point(cloud.scan.points[0], [2.5, 0.0, 0.2]);
        assert_point(cloud.scan.points[1], [0.0, 1.8, 0.0]);
        assert_point(cloud.scan.points[2], [-1.4, 0.0, 0.0]);
        assert_eq!(channel(cloud, "sensor_index"), &[0.0, 1.0, 2.0]);
        assert_eq!(channel(cloud, "strength"), &[500.0, 500.0, 300.0]);
        let time = channel(cloud, "device_time_ms");
        assert!(time[0].is_nan() && time[1] == 10.0 * k as f32 && time[2].is_nan());
        // Stamped by the cycle's first frame.
        assert_eq!(cloud.received, host(10 * k as u64 + 1));
    }
    assert_eq!(d.stats().total_errors(), 0);
    assert!(d.missing_by_sensor().iter().all(|(_, n)| *n == 0));
}

#[test]
fn a_silent_sensor_closes_the_cycle_on_timeout_and_is_counted() {
    let mut d = three();
    receive(&mut d, le_frame(0x003, 200, 500, None), 1);
    receive(&mut d, le_frame(0x004, 150, 500, Some(1)), 2);
    let mut out = Vec::new();
    d.poll(host(50), &mut out);
    assert!(clouds(&out).is_empty(), "49 ms after the first reading");
    d.poll(host(51), &mut out);
    let c = clouds(&out);
    assert_eq!(c.len(), 1);
    assert_eq!(c[0].scan.points.len(), 2);
    assert_eq!(d.stats().errors("missing_reading"), 1);
    assert_eq!(
        d.missing_by_sensor(),
        &[
            ("front".to_owned(), 0),
            ("left".to_owned(), 0),
            ("rear".to_owned(), 1)
        ]
    );
}

#[test]
fn a_sensor_reporting_twice_closes_the_cycle_without_the_others() {
    let mut d = three();
    receive(&mut d, le_frame(0x003, 200, 500, None), 1);
    let out = receive(&mut d, le_frame(0x003, 210, 500, None), 11);
    let c = clouds(&out);
    assert_eq!(c.len(), 1, "the first cycle, with front only");
    assert_eq!(c[0].scan.points.len(), 1);
    assert_point(c[0].scan.points[0], [2.5, 0.0, 0.2]);
    assert_eq!(d.stats().errors("missing_reading"), 2);
    // The second reading started the next cycle.
    receive(&mut d, le_frame(0x004, 150, 500, Some(1)), 12);
    let c = clouds(&receive(
        &mut d,
        tf02_frame(0x0009_0002, 100, 300, 3, 8),
        13,
    ));
    assert_eq!(c.len(), 1);
    assert_point(c[0].scan.points[0], [2.6, 0.0, 0.2]);
    assert_eq!(c[0].received, host(11));
}

#[test]
fn silence_is_recovering_until_a_frame_returns() {
    let mut d = three();
    let mut out = Vec::new();
    d.poll(host(999), &mut out);
    assert!(out.is_empty());
    d.poll(host(1000), &mut out);
    d.poll(host(1100), &mut out);
    assert_eq!(
        out,
        vec![CanDriverOutput::State(DeviceState::Recovering(
            "no frames from the rangefinders for 1.0 s".into()
        ))]
    );
    assert_eq!(d.stats().errors("silent"), 1);
    let out = receive(&mut d, le_frame(0x003, 200, 500, None), 1200);
    assert_eq!(out[0], CanDriverOutput::State(DeviceState::Streaming));
}

#[test]
fn bad_configurations_are_named() {
    let mount = MountPose::default();
    let err = |sensors| BenewakeCanDriver::new(BenewakeCanConfig::new(sensors)).unwrap_err();
    assert!(matches!(
        err(vec![]),
        BenewakeCanError::SensorCount { found: 0, .. }
    ));
    let many = (0..17)
        .map(|k| sensor(&format!("s{k}"), Model::Tf03, k, mount))
        .collect();
    assert!(matches!(
        err(many),
        BenewakeCanError::SensorCount { found: 17, .. }
    ));
    let twins = vec![
        sensor("a", Model::Tf03, 3, mount),
        sensor("b", Model::TfminiI, 3, mount),
    ];
    let e = err(twins);
    assert!(
        matches!(&e, BenewakeCanError::DuplicateId { first, second, .. } if first == "a" && second == "b"),
        "{e}"
    );
    // The same number on a standard and an extended id are two ids.
    let mut ext = sensor("b", Model::Tf03, 3, mount);
    ext.extended = true;
    assert!(BenewakeCanDriver::new(BenewakeCanConfig::new(vec![
        sensor("a", Model::Tf03, 3, mount),
        ext
    ]))
    .is_ok());
    let e = err(vec![sensor("a", Model::Tf03, 0x800, mount)]);
    assert!(matches!(e, BenewakeCanError::BadId { .. }), "{e}");
    let e = err(vec![
        sensor("a", Model::Tf03, 3, mount),
        sensor("a", Model::Tf03, 4, mount),
    ]);
    assert!(e.to_string().contains("two sensors are named a"), "{e}");
}

#[test]
fn disconnect_cuts_the_open_cycle() {
    let mut d = three();
    receive(&mut d, le_frame(0x003, 200, 500, None), 1);
    let mut out = Vec::new();
    d.disconnect(&mut out);
    assert!(clouds(&out).is_empty());
    assert_eq!(d.stats().notes("cycle_cut"), 1);
    assert_eq!(d.stats().errors("missing_reading"), 0);
}
