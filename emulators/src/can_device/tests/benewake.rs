//! Benewake CAN emulator tests.

use super::{frame, run, run_past};
use crate::can_device::benewake::{range_noise_m, BenewakeCanModel};
use crate::can_device::{
    can_emulator, CanDeviceEmulator, CanEmulatorOptions, CanWorld, RangefinderSpec,
};
use shroud_drivers::assembly::MountPose;
use shroud_drivers::can::CanFrame;
use shroud_drivers::dbc::builtin;
use shroud_shapes::format::TriangleMesh;
use shroud_sim::Bvh;
use std::sync::Arc;

/// A wall facing the origin: the plane x = `x`, 200 m square.
fn wall(x: f64) -> Arc<Bvh> {
    let vertices = vec![
        [x, -100.0, -100.0],
        [x, 100.0, -100.0],
        [x, 100.0, 100.0],
        [x, -100.0, 100.0],
    ];
    Arc::new(Bvh::build(&TriangleMesh::from_quads(vertices, &[[0, 1, 2, 3]])).unwrap())
}

fn world(mesh: Option<Arc<Bvh>>) -> CanWorld {
    CanWorld {
        mesh,
        ..CanWorld::default()
    }
}

fn device(
    model: &str,
    mesh: Option<Arc<Bvh>>,
    options: &CanEmulatorOptions,
) -> Box<dyn CanDeviceEmulator> {
    can_emulator(model, options, world(mesh)).unwrap()
}

fn at(id: u32, extended: bool, x: f64) -> RangefinderSpec {
    RangefinderSpec {
        id,
        extended,
        mount: MountPose::from_xyz_rpy([x, 0.0, 0.0], [0.0; 3]),
    }
}

/// Dist, in cm, a reading at `range_m` may carry: the noise (5 σ) and the
/// 1 cm step.
fn tolerance_cm(range_m: f64) -> f64 {
    5.0 * range_noise_m(range_m) * 100.0 + 1.0
}

fn decoded(name: &str, f: &CanFrame, signal: &str) -> f64 {
    let db = builtin(name).unwrap();
    let spec = db.messages().first().unwrap();
    spec.decode(f).unwrap().get(signal).unwrap()
}

#[test]
fn tf03_reports_the_ray_cast_distance_at_100_hz() {
    let mut tf03 = device("tf03-can", Some(wall(5.0)), &CanEmulatorOptions::default());
    let frames = run_past(tf03.as_mut(), 1.0);
    assert_eq!(frames.len(), 100);
    for (t, f) in &frames {
        assert_eq!((f.id, f.extended, f.len), (0x003, false, 6));
        // Hand layout (TF03 V1.2.2 Table 7): Dist LE in bytes 0-1, Strength
        // LE in bytes 2-3.
        let dist = f64::from(u16::from_le_bytes([f.data[0], f.data[1]]));
        let strength = f64::from(u16::from_le_bytes([f.data[2], f.data[3]]));
        assert_eq!(decoded("benewake_tf03", f, "Dist"), dist);
        assert_eq!(decoded("benewake_tf03", f, "Strength"), strength);
        assert!((dist - 500.0).abs() <= tolerance_cm(5.0), "{dist} at {t}");
        assert!((40.0..=3500.0).contains(&strength), "{strength}");
    }
    let gaps: Vec<f64> = frames.windows(2).map(|w| w[1].0 - w[0].0).collect();
    assert!(gaps.iter().all(|g| (g - 0.01).abs() < 1e-9), "{gaps:?}");
}

#[test]
fn tfmini_i_reports_distance_and_a_millisecond_timestamp() {
    let mut tfmini = device(
        "tfmini-i-can",
        Some(wall(3.0)),
        &CanEmulatorOptions::default(),
    );
    let frames = run_past(tfmini.as_mut(), 0.5);
    assert_eq!(frames.len(), 50);
    for (t, f) in &frames {
        assert_eq!((f.id, f.extended), (0x003, false));
        let dist = f64::from(u16::from_le_bytes([f.data[0], f.data[1]]));
        let stamp = u32::from_le_bytes([f.data[4], f.data[5], f.data[6], f.data[7]]);
        assert_eq!(decoded("benewake_tfmini_i", f, "Dist"), dist);
        assert_eq!(
            decoded("benewake_tfmini_i", f, "Timestamp"),
            f64::from(stamp)
        );
        assert!((dist - 300.0).abs() <= tolerance_cm(3.0), "{dist}");
        // Measured, then sent: the stamp precedes the send by one frame
        // time at 250 kbit/s (under 1 ms).
        let sent_ms = t * 1000.0;
        assert!(
            f64::from(stamp) <= sent_ms + 0.5 && f64::from(stamp) >= sent_ms - 1.5,
            "{stamp} {sent_ms}"
        );
    }
}

#[test]
fn tf02_sends_big_endian_on_its_extended_id_with_reliability() {
    let mut tf02 = device("tf02-can", Some(wall(10.0)), &CanEmulatorOptions::default());
    let frames = run_past(tf02.as_mut(), 0.3);
    assert_eq!(frames.len(), 30);
    for (_, f) in &frames {
        assert_eq!((f.id, f.extended), (0x0009_0002, true));
        // Hand layout (TF02 manual §4.2): B0 DIST_H, B1 DIST_L, B2-3
        // STRENGTH big-endian, B4 exposure, B5 SIG.
        let dist = f64::from(u16::from_be_bytes([f.data[0], f.data[1]]));
        let strength = f64::from(u16::from_be_bytes([f.data[2], f.data[3]]));
        assert_eq!(decoded("benewake_tf02", f, "Dist"), dist);
        assert_eq!(decoded("benewake_tf02", f, "Strength"), strength);
        assert_eq!(
            decoded("benewake_tf02", f, "ExposureTime"),
            f64::from(f.data[4])
        );
        assert_eq!(
            decoded("benewake_tf02", f, "Reliability"),
            f64::from(f.data[5])
        );
        assert!((dist - 1000.0).abs() <= tolerance_cm(10.0), "{dist}");
        assert!(f.data[5] == 7 || f.data[5] == 8, "reliable: {}", f.data[5]);
        assert!(f.data[4] == 3 || f.data[4] == 6);
    }
}

#[test]
fn tf02_i_reports_the_ray_cast_distance() {
    let mut tf02i = device(
        "tf02-i-can",
        Some(wall(25.0)),
        &CanEmulatorOptions::default(),
    );
    let frames = run_past(tf02i.as_mut(), 0.2);
    assert_eq!(frames.len(), 20);
    for (_, f) in &frames {
        let dist = decoded("benewake_tfmini_i", f, "Dist");
        assert!((dist - 2500.0).abs() <= tolerance_cm(25.0), "{dist}");
    }
}

#[test]
fn nothing_hit_reads_as_each_models_invalid_value() {
    // TF03: the over-range value 18000; TFmini-i: 0; TF02-i: 4500; TF02: 22 m
    // with an unreliable SIG.
    for (model, dbc, invalid, min_strength) in [
        ("tf03-can", "benewake_tf03", 18000.0, 40.0),
        ("tfmini-i-can", "benewake_tfmini_i", 0.0, 100.0),
        ("tf02-i-can", "benewake_tfmini_i", 4500.0, 60.0),
        ("tf02-can", "benewake_tf02", 2200.0, 60.0),
    ] {
        let model_info = BenewakeCanModel::from_name(model).unwrap();
        assert_eq!(model_info.invalid_cm() as f64, invalid);
        for mesh in [None, Some(wall(500.0))] {
            let mut device = device(model, mesh, &CanEmulatorOptions::default());
            let frames = run_past(device.as_mut(), 0.1);
            assert_eq!(frames.len(), 10, "{model}");
            for (_, f) in &frames {
                assert_eq!(decoded(dbc, f, "Dist"), invalid, "{model}");
                assert!(decoded(dbc, f, "Strength") < min_strength, "{model}");
                if model == "tf02-can" {
                    assert!(decoded(dbc, f, "Reliability") <= 6.0);
                }
            }
        }
    }
}

#[test]
fn three_rangefinders_share_the_bus_on_distinct_ids_taking_turns() {
    // Walls at x = 8 m; the units sit at x = 0, 2, 4 m, so they read 8, 6, 4 m.
    let options = CanEmulatorOptions {
        rangefinders: vec![
            at(0x10, false, 0.0),
            at(0x11, false, 2.0),
            at(0x12, false, 4.0),
        ],
        ..CanEmulatorOptions::default()
    };
    let mut tf03 = device("tf03-can", Some(wall(8.0)), &options);
    // Round 100 ends at 1.0067 s.
    let frames = run(tf03.as_mut(), 1.008);
    assert_eq!(frames.len(), 300);
    for (unit, (id, range)) in [(0x10, 8.0), (0x11, 6.0), (0x12, 4.0)]
        .into_iter()
        .enumerate()
    {
        let mine: Vec<&(f64, CanFrame)> = frames.iter().filter(|(_, f)| f.id == id).collect();
        assert_eq!(mine.len(), 100, "unit {unit}");
        for (_, f) in &mine {
            let dist = decoded("benewake_tf03", f, "Dist");
            assert!(
                (dist - range * 100.0).abs() <= tolerance_cm(range),
                "{id:#x}: {dist}"
            );
        }
    }
    // In turn: 0x10, 0x11, 0x12, 0x10, ...
    for (k, (_, f)) in frames.iter().enumerate() {
        assert_eq!(f.id, 0x10 + (k % 3) as u32);
    }
}

#[test]
fn tf03_takes_a_new_send_id_when_saved() {
    let mut tf03 = device("tf03-can", Some(wall(5.0)), &CanEmulatorOptions::default());
    run(tf03.as_mut(), 0.1);
    // 5A 08 50 <0x005 LE> SU on the RX id 0x3003 (an extended frame: 0x3003
    // does not fit 11 bits). Sum 5A+08+50+05 = B7.
    tf03.receive(&frame(0x3003, true, "5A085005000000B7"), 0.1);
    let between = run(tf03.as_mut(), 0.2);
    let reply = frame(0x003, false, "5A055000AF");
    assert_eq!(between.iter().filter(|(_, f)| *f == reply).count(), 1);
    assert!(
        between.iter().all(|(_, f)| f.id == 0x003),
        "not before the save"
    );
    // Save: 5A 04 11 6F, answered 5A 05 11 00 70 on the old id.
    tf03.receive(&frame(0x3003, true, "5A04116F"), 0.2);
    let after = run(tf03.as_mut(), 0.4);
    let saved = after
        .iter()
        .position(|(_, f)| *f == frame(0x003, false, "5A05110070"))
        .unwrap();
    // Only the reading measured with the command (at 0.2 s) precedes it.
    assert!(saved <= 1);
    let readings: Vec<&CanFrame> = after.iter().skip(saved + 1).map(|(_, f)| f).collect();
    assert!(readings.len() >= 19);
    assert!(readings.iter().all(|f| f.id == 0x005 && !f.extended));
    // Commands still come on the RX id; now extended frames (5D 01), saved.
    tf03.receive(&frame(0x3003, true, "5A055D01BD"), 0.4);
    tf03.receive(&frame(0x3003, true, "5A04116F"), 0.4);
    let extended = run(tf03.as_mut(), 0.6);
    assert!(extended
        .iter()
        .any(|(_, f)| *f == frame(0x005, false, "5A055D00BC")));
    assert!(extended
        .iter()
        .rev()
        .take(10)
        .all(|(_, f)| f.id == 0x005 && f.extended));
}

#[test]
fn tfmini_i_takes_its_can_setting_across_two_frames_then_the_save() {
    let mut tfmini = device(
        "tfmini-i-can",
        Some(wall(2.0)),
        &CanEmulatorOptions::default(),
    );
    // sensors.md §2.1's example: std, 500 kbit/s, RX 0x10, TX 0x20 (14 bytes).
    tfmini.receive(&frame(0x003, false, "5A0E510005100000"), 0.05);
    tfmini.receive(&frame(0x003, false, "0020000000EE"), 0.05);
    let echo = run(tfmini.as_mut(), 0.1);
    let replies: Vec<CanFrame> = echo
        .iter()
        .map(|(_, f)| *f)
        .filter(|f| f.data[0] == 0x5A || f.len == 6)
        .collect();
    assert!(replies.contains(&frame(0x003, false, "5A0E510005100000")));
    assert!(replies.contains(&frame(0x003, false, "0020000000EE")));
    tfmini.receive(&frame(0x003, false, "5A04116F"), 0.1);
    let after = run(tfmini.as_mut(), 0.3);
    let saved = after
        .iter()
        .position(|(_, f)| *f == frame(0x003, false, "5A05110070"))
        .unwrap();
    assert!(saved <= 1);
    assert!(after.iter().skip(saved + 1).all(|(_, f)| f.id == 0x20));
    assert!(after.len() - saved > 19);
    // Commands now go to 0x10; the old id is no longer heard.
    tfmini.receive(&frame(0x003, false, "5A04106E"), 0.3);
    assert!(run(tfmini.as_mut(), 0.35)
        .iter()
        .all(|(_, f)| f.id == 0x20 && f.len == 8));
    tfmini.receive(&frame(0x010, false, "5A04106E"), 0.35);
    let reset = run(tfmini.as_mut(), 0.5);
    let done = reset
        .iter()
        .position(|(_, f)| *f == frame(0x020, false, "5A0510006F"))
        .unwrap();
    assert!(done <= 1);
    assert!(
        reset.iter().skip(done + 1).all(|(_, f)| f.id == 0x003),
        "factory ids again"
    );
}

#[test]
fn a_bad_sum_or_a_foreign_id_gets_no_reply() {
    let mut tf03 = device("tf03-can", Some(wall(5.0)), &CanEmulatorOptions::default());
    tf03.receive(&frame(0x3003, true, "5A04116E"), 0.0);
    tf03.receive(&frame(0x3004, true, "5A04116F"), 0.0);
    let frames = run_past(tf03.as_mut(), 0.1);
    assert!(frames.iter().all(|(_, f)| f.data[0] != 0x5A || f.len == 8));
    assert_eq!(frames.len(), 10);
}

#[test]
fn drop_frame_every_skips_one_reading_every_nth_round() {
    let options = CanEmulatorOptions {
        rangefinders: vec![
            at(0x10, false, 0.0),
            at(0x11, false, 0.0),
            at(0x12, false, 0.0),
        ],
        drop_frame_every: 2,
        ..CanEmulatorOptions::default()
    };
    let mut tf03 = device("tf03-can", Some(wall(8.0)), &options);
    // 9 rounds of 3 (the 9th at 90, 93.3, 96.7 ms); rounds 2, 4, 6, 8 lose
    // the middle unit's reading.
    let frames = run(tf03.as_mut(), 0.099);
    let count = |id: u32| frames.iter().filter(|(_, f)| f.id == id).count();
    assert_eq!((count(0x10), count(0x11), count(0x12)), (9, 5, 9));
}

#[test]
fn bad_rangefinder_lists_are_errors() {
    let twice = CanEmulatorOptions {
        rangefinders: vec![at(0x10, false, 0.0), at(0x10, false, 1.0)],
        ..CanEmulatorOptions::default()
    };
    assert!(can_emulator("tf03-can", &twice, world(None)).is_err());
    let too_big = CanEmulatorOptions {
        rangefinders: vec![at(0x800, false, 0.0)],
        ..CanEmulatorOptions::default()
    };
    assert!(can_emulator("tfmini-i-can", &too_big, world(None)).is_err());
    let many = CanEmulatorOptions {
        rangefinders: (0..17).map(|i| at(i, false, 0.0)).collect(),
        ..CanEmulatorOptions::default()
    };
    assert!(can_emulator("tf03-can", &many, world(None)).is_err());
}
