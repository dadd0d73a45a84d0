//! Tests of the RPLIDAR emulator: golden vectors from the protocol, whole
//! sessions decoded by the independent test-side decoder in `decode`, the
//! state machine (motor, reset, faults) and property tests.

mod decode;
mod world;

use proptest::prelude::*;

use super::capsule::{self, LegacySample};
use super::emulator::BOOT_S;
use super::node::Node;
use super::request::{Request, RequestParser};
use super::tx::TX_CAPACITY;
use super::*;
use crate::device::{Faults, RaySource, SerialDeviceEmulator};
use world::{Flower, Recorder, Void};

/// No noise, no dropouts.
fn quiet() -> RplidarOptions {
    RplidarOptions {
        noise: 0.0,
        dropout: 0.0,
        ..RplidarOptions::default()
    }
}

fn device(
    model: RplidarModel,
    rays: impl RaySource + 'static,
    options: RplidarOptions,
) -> RplidarEmulator {
    RplidarEmulator::new(model, Box::new(rays), options)
}

/// A request with payload: A5 cmd size payload xor (computed here).
fn request(cmd: u8, payload: &[u8]) -> Vec<u8> {
    let mut bytes = vec![0xA5, cmd, payload.len() as u8];
    bytes.extend_from_slice(payload);
    let xor = bytes.iter().fold(0u8, |acc, b| acc ^ b);
    bytes.push(xor);
    bytes
}

fn poll(emulator: &mut RplidarEmulator, at: f64) -> Vec<u8> {
    let mut out = Vec::new();
    emulator.poll(at, &mut out);
    out
}

fn exchange(emulator: &mut RplidarEmulator, bytes: &[u8], at: f64) -> Vec<u8> {
    emulator.receive(bytes, at);
    poll(emulator, at)
}

/// Polls every 50 ms from `from` to `to`, concatenating the output.
fn run(emulator: &mut RplidarEmulator, from: f64, to: f64) -> Vec<u8> {
    let mut out = Vec::new();
    let mut t = from;
    while t < to {
        t = (t + 0.05).min(to);
        emulator.poll(t, &mut out);
    }
    out
}

fn nodes(stream: &[u8]) -> Vec<decode::Node> {
    stream
        .chunks_exact(5)
        .filter_map(|chunk| chunk.try_into().ok())
        .map(|bytes: [u8; 5]| decode::node(&bytes))
        .collect()
}

fn capsules(stream: &[u8]) -> Vec<decode::Capsule> {
    stream
        .chunks_exact(84)
        .filter_map(decode::capsule)
        .collect()
}

const EXPRESS_LEGACY: [u8; 9] = [0xA5, 0x82, 0x05, 0x00, 0x00, 0x00, 0x00, 0x00, 0x22];

// ---- golden vectors -------------------------------------------------------

#[test]
fn standard_node_golden_vector() {
    let node = Node {
        angle_q6: 5792,
        distance_q2: 4937,
        quality: 15,
        start: true,
    };
    let bytes = node.encode(false);
    assert_eq!(bytes, [0x3D, 0x41, 0x2D, 0x49, 0x13]);
    let decoded = decode::node(&bytes);
    assert_eq!(decoded.quality, 15);
    assert!(decoded.start && decoded.valid);
    assert_eq!(decoded.angle_deg, 90.5);
    assert_eq!(decoded.distance_mm, 1234.25);
}

#[test]
fn express_request_is_answered_with_the_legacy_descriptor() {
    assert_eq!(request(0x82, &[0, 0, 0, 0, 0]), EXPRESS_LEGACY);
    let mut lidar = device(RplidarModel::A1, Flower, quiet());
    let out = exchange(&mut lidar, &EXPRESS_LEGACY, 1.0);
    assert_eq!(out, [0xA5, 0x5A, 0x54, 0x00, 0x00, 0x40, 0x82]);
    assert!(lidar.is_scanning());
}

#[test]
fn scan_descriptor_golden_vector() {
    let mut lidar = device(RplidarModel::A2, Flower, quiet());
    let out = exchange(&mut lidar, &[0xA5, 0x20], 1.0);
    assert_eq!(out, [0xA5, 0x5A, 0x05, 0x00, 0x00, 0x40, 0x81]);
}

#[test]
fn get_health_golden_vectors() {
    let mut lidar = device(RplidarModel::A1, Flower, quiet());
    let out = exchange(&mut lidar, &[0xA5, 0x52], 0.1);
    assert_eq!(
        out,
        [0xA5, 0x5A, 0x03, 0x00, 0x00, 0x00, 0x06, 0x00, 0x00, 0x00]
    );

    let warning = RplidarOptions {
        health: RplidarHealth::Warning(0x1234),
        ..quiet()
    };
    let mut lidar = device(RplidarModel::A1, Flower, warning);
    let out = exchange(&mut lidar, &[0xA5, 0x52], 0.1);
    assert_eq!(
        out,
        [0xA5, 0x5A, 0x03, 0x00, 0x00, 0x00, 0x06, 0x01, 0x34, 0x12]
    );
}

#[test]
fn get_info_golden_vectors() {
    for (model, id, hardware) in [(RplidarModel::A1, 0x18, 7), (RplidarModel::A2, 0x28, 5)] {
        let mut lidar = device(model, Flower, quiet());
        let out = exchange(&mut lidar, &[0xA5, 0x50], 0.1);
        assert_eq!(out.len(), 7 + 20);
        assert_eq!(out[..7], [0xA5, 0x5A, 0x14, 0x00, 0x00, 0x00, 0x04]);
        // model, firmware minor 29 (0x1D), major 1, hardware.
        assert_eq!(out[7..11], [id, 0x1D, 0x01, hardware]);
    }
}

#[test]
fn serial_number_depends_on_the_seed() {
    let info = |seed| {
        let options = RplidarOptions { seed, ..quiet() };
        let mut lidar = device(RplidarModel::A1, Flower, options);
        exchange(&mut lidar, &[0xA5, 0x50], 0.1)[11..].to_vec()
    };
    assert_eq!(info(1), info(1));
    assert_ne!(info(1), info(2));
}

#[test]
fn get_samplerate_golden_vector() {
    let mut lidar = device(RplidarModel::A1, Flower, quiet());
    let out = exchange(&mut lidar, &[0xA5, 0x59], 0.1);
    // 500 µs standard, 250 µs express.
    assert_eq!(
        out,
        [0xA5, 0x5A, 0x04, 0x00, 0x00, 0x00, 0x15, 0xF4, 0x01, 0xFA, 0x00]
    );
}

/// Worked by hand: start 90° (q6 0x1680) with S → 80 96; cabin 0 empty;
/// cabins 1..15 hold 1000 mm (0x0FA0) with dθ 0x15 and 0x2A: words 0x0FA1
/// and 0x0FA2, offsets 0x5 | 0xA << 4 = 0xA5. Checksum: 0x80 ^ 0x96 ^ (odd
/// count of A1^0F^A2^0F^A5 = 0xA6) = 0xB0 → A0 5B.
#[test]
fn legacy_capsule_checked_by_hand() {
    let mut samples = [LegacySample {
        distance_mm: 1000,
        dtheta_q3: 0x15,
    }; 32];
    for odd in samples.iter_mut().skip(1).step_by(2) {
        odd.dtheta_q3 = 0x2A;
    }
    samples[0] = LegacySample::default();
    samples[1] = LegacySample::default();
    let mut expected = vec![0xA0, 0x5B, 0x80, 0x96, 0, 0, 0, 0, 0];
    for _ in 1..16 {
        expected.extend_from_slice(&[0xA1, 0x0F, 0xA2, 0x0F, 0xA5]);
    }
    assert_eq!(capsule::legacy(5760, true, &samples).to_vec(), expected);
}

/// By hand: start 1° (q6 0x40), no S → 40 00; first distance 1000 mm (E8
/// 03), the rest 0. Checksum 0x40 ^ 0xE8 ^ 0x03 = 0xAB → AB 5A.
#[test]
fn dense_capsule_checked_by_hand() {
    let mut distances = [0u16; 40];
    distances[0] = 1000;
    let mut expected = vec![0xAB, 0x5A, 0x40, 0x00, 0xE8, 0x03];
    expected.resize(84, 0);
    assert_eq!(capsule::dense(0x40, false, &distances).to_vec(), expected);
}

// ---- whole sessions, decoded ----------------------------------------------

#[test]
fn standard_scan_decodes_to_the_world() {
    let mut lidar = device(RplidarModel::A1, Flower, quiet());
    let mut out = exchange(&mut lidar, &[0xA5, 0x20], 1.0);
    out.extend(run(&mut lidar, 1.0, 3.0));
    let d = decode::descriptor(&out).expect("descriptor");
    assert_eq!((d.len, d.looping, d.answer_type), (5, true, 0x81));
    let nodes = nodes(&out[7..]);
    // 2 s at 500 µs a sample.
    assert!((3990..=4000).contains(&nodes.len()), "{}", nodes.len());
    for node in &nodes {
        assert!(node.valid);
        let expected = Flower::range_cw(node.angle_deg) * 1000.0;
        assert!(
            (node.distance_mm - expected).abs() < 0.5,
            "{node:?} vs {expected}"
        );
        assert!(node.quality > 0);
    }
    // One S per turn: 5.5 Hz at 2000 samples/s is 363.6 samples a turn.
    let starts: Vec<usize> = (0..nodes.len()).filter(|&i| nodes[i].start).collect();
    assert!((10..=12).contains(&starts.len()), "{starts:?}");
    for gap in starts.windows(2) {
        assert!((363..=364).contains(&(gap[1] - gap[0])), "{starts:?}");
    }
}

#[test]
fn legacy_express_decodes_to_the_world_with_unsigned_dtheta() {
    let mut lidar = device(RplidarModel::A1, Flower, quiet());
    let mut out = exchange(&mut lidar, &EXPRESS_LEGACY, 1.0);
    out.extend(run(&mut lidar, 1.0, 2.0));
    let capsules = capsules(&out[7..]);
    // 1 s at 250 µs a sample, 32 samples a capsule.
    assert_eq!(capsules.len(), 125);
    assert!(capsules.iter().all(|c| c.checksum_ok));
    assert!(capsules[0].new_scan && capsules[1..].iter().all(|c| !c.new_scan));
    let largest_dtheta = capsules
        .iter()
        .flat_map(decode::legacy_samples)
        .map(|(_, dtheta)| dtheta)
        .fold(0.0, f64::max);
    // The 0.2 m parts of the wall need dθ above 4° (bit 5 set).
    assert!(largest_dtheta > 4.0, "{largest_dtheta}");
    let points = decode::points(&capsules, false);
    assert_eq!(points.len(), 124 * 32);
    for (angle, distance) in points {
        let expected = Flower::range_cw(angle) * 1000.0;
        assert!(
            (distance - expected).abs() < 3.0,
            "{angle}: {distance} vs {expected}"
        );
    }
}

#[test]
fn a2_typical_mode_is_dense_and_decodes_to_the_world() {
    let mut lidar = device(RplidarModel::A2, Flower, quiet());
    let typical = exchange(&mut lidar, &request(0x84, &[0x7C, 0, 0, 0]), 1.0);
    assert_eq!(
        typical,
        [0xA5, 0x5A, 0x06, 0, 0, 0, 0x20, 0x7C, 0, 0, 0, 3, 0]
    );
    let answer_type = exchange(&mut lidar, &request(0x84, &[0x75, 0, 0, 0, 3, 0]), 1.0);
    assert_eq!(
        answer_type,
        [0xA5, 0x5A, 0x05, 0, 0, 0, 0x20, 0x75, 0, 0, 0, 0x85]
    );

    let mut out = exchange(&mut lidar, &request(0x82, &[3, 0, 0, 0, 0]), 1.0);
    assert_eq!(out[..7], [0xA5, 0x5A, 0x54, 0x00, 0x00, 0x40, 0x85]);
    out.extend(run(&mut lidar, 1.0, 2.0));
    let capsules = capsules(&out[7..]);
    // 1 s at 200 µs a sample, 40 samples a capsule.
    assert_eq!(capsules.len(), 125);
    let points = decode::points(&capsules, true);
    for (angle, distance) in points {
        let expected = Flower::range_cw(angle) * 1000.0;
        assert!(
            (distance - expected).abs() < 2.0,
            "{angle}: {distance} vs {expected}"
        );
    }
}

#[test]
fn a2_scan_mode_table() {
    let mut lidar = device(RplidarModel::A2, Flower, quiet());
    let conf = |lidar: &mut RplidarEmulator, key: u8, mode: u16| {
        let [m0, m1] = mode.to_le_bytes();
        let out = exchange(lidar, &request(0x84, &[key, 0, 0, 0, m0, m1]), 1.0);
        assert_eq!(out[6], 0x20);
        assert_eq!(out[7..11], [key, 0, 0, 0]);
        out[11..].to_vec()
    };
    assert_eq!(conf(&mut lidar, 0x70, 0), [4, 0]);
    let names: Vec<Vec<u8>> = (0..4).map(|mode| conf(&mut lidar, 0x7F, mode)).collect();
    assert_eq!(names[0], b"Standard\0");
    assert_eq!(names[1], b"Express\0");
    assert_eq!(names[3], b"Sensitivity\0");
    // Express: 250 µs q8 = 64000 (the PDF's own example).
    assert_eq!(conf(&mut lidar, 0x71, 1), 64000u32.to_le_bytes());
    assert_eq!(conf(&mut lidar, 0x74, 1), (12u32 << 8).to_le_bytes());
    assert_eq!(conf(&mut lidar, 0x75, 0), [0x81]);
    assert_eq!(conf(&mut lidar, 0x75, 1), [0x82]);
    // Unknown mode or key: no answer.
    assert!(exchange(&mut lidar, &request(0x84, &[0x75, 0, 0, 0, 9, 0]), 1.0).is_empty());
    assert!(exchange(&mut lidar, &request(0x84, &[0x01, 0, 0, 0]), 1.0).is_empty());
    assert_eq!(lidar.rejects().get(RejectKind::BadPayload), 2);
}

#[test]
fn a1_typical_mode_is_legacy_express() {
    let mut lidar = device(RplidarModel::A1, Flower, quiet());
    let typical = exchange(&mut lidar, &request(0x84, &[0x7C, 0, 0, 0]), 1.0);
    assert_eq!(typical[11..], [1, 0]);
    let out = exchange(&mut lidar, &request(0x82, &[1, 0, 0, 0, 0]), 1.0);
    assert_eq!(out, [0xA5, 0x5A, 0x54, 0x00, 0x00, 0x40, 0x82]);
}

// ---- state machine --------------------------------------------------------

#[test]
fn acc_board_flag_on_a2_only() {
    let ask = request(0xFF, &[0, 0, 0, 0]);
    let mut a2 = device(RplidarModel::A2, Flower, quiet());
    assert_eq!(
        exchange(&mut a2, &ask, 0.1),
        [0xA5, 0x5A, 0x04, 0, 0, 0, 0xFF, 0x01, 0, 0, 0]
    );
    let mut a1 = device(RplidarModel::A1, Flower, quiet());
    assert!(exchange(&mut a1, &ask, 0.1).is_empty());
    assert_eq!(a1.rejects().get(RejectKind::Unsupported), 1);
}

#[test]
fn bad_checksum_and_unknown_commands_are_ignored() {
    let mut lidar = device(RplidarModel::A1, Flower, quiet());
    let mut bad = EXPRESS_LEGACY;
    bad[8] ^= 0x01;
    assert!(exchange(&mut lidar, &bad, 1.0).is_empty());
    assert!(!lidar.is_scanning());
    assert!(exchange(&mut lidar, &[0xA5, 0x33], 1.0).is_empty());
    assert!(exchange(&mut lidar, &[0x00, 0x5A], 1.0).is_empty());
    assert_eq!(lidar.rejects().get(RejectKind::BadChecksum), 1);
    assert_eq!(lidar.rejects().get(RejectKind::UnknownCommand), 1);
    assert_eq!(lidar.rejects().get(RejectKind::StrayByte), 2);
    // The device still answers afterwards.
    assert_eq!(exchange(&mut lidar, &[0xA5, 0x52], 1.0).len(), 10);
}

#[test]
fn an_unknown_command_does_not_stop_a_scan() {
    let mut lidar = device(RplidarModel::A1, Flower, quiet());
    exchange(&mut lidar, &[0xA5, 0x20], 1.0);
    exchange(&mut lidar, &[0xA5, 0x33], 1.5);
    assert!(lidar.is_scanning());
    assert!(!poll(&mut lidar, 2.0).is_empty());
}

#[test]
fn a_split_request_is_reassembled_and_a_stale_one_dropped() {
    let mut lidar = device(RplidarModel::A1, Flower, quiet());
    assert!(exchange(&mut lidar, &EXPRESS_LEGACY[..4], 1.0).is_empty());
    assert_eq!(exchange(&mut lidar, &EXPRESS_LEGACY[4..], 1.1).len(), 7);
    exchange(&mut lidar, &[0xA5, 0x25], 1.2);
    assert!(exchange(&mut lidar, &EXPRESS_LEGACY[..4], 2.0).is_empty());
    assert!(exchange(&mut lidar, &EXPRESS_LEGACY[4..], 7.5).is_empty());
    assert_eq!(lidar.rejects().get(RejectKind::RequestTimeout), 1);
}

#[test]
fn stop_ends_the_stream() {
    let mut lidar = device(RplidarModel::A1, Flower, quiet());
    exchange(&mut lidar, &[0xA5, 0x20], 1.0);
    assert!(!exchange(&mut lidar, &[0xA5, 0x25], 1.5).is_empty());
    assert!(!lidar.is_scanning());
    assert!(poll(&mut lidar, 3.0).is_empty());
}

#[test]
fn a_single_request_ends_the_scan_and_is_answered_after_its_data() {
    let mut lidar = device(RplidarModel::A1, Flower, quiet());
    exchange(&mut lidar, &[0xA5, 0x20], 1.0);
    let out = exchange(&mut lidar, &[0xA5, 0x52], 1.5);
    // 1000 nodes, then the 10-byte health answer.
    assert_eq!(out.len(), 1000 * 5 + 10);
    assert_eq!(
        out[out.len() - 10..out.len() - 3],
        [0xA5, 0x5A, 3, 0, 0, 0, 6]
    );
    assert!(!lidar.is_scanning());
    assert!(poll(&mut lidar, 2.0).is_empty());
}

#[test]
fn streaming_continues_while_nobody_reads_and_a_stalled_host_loses_data() {
    let mut lidar = device(RplidarModel::A1, Flower, quiet());
    lidar.receive(&[0xA5, 0x20], 1.0);
    // Nobody polls for 0.9 s: every node of it is still delivered.
    assert_eq!(poll(&mut lidar, 1.9).len(), 7 + 1800 * 5);
    // Nobody polls for 100 s: only about the last second arrives.
    let late = poll(&mut lidar, 101.9);
    assert!(late.len() <= 2001 * 5, "{}", late.len());
    assert!(late.len() >= 1999 * 5, "{}", late.len());
    assert!(lidar.rejects().get(RejectKind::StalledHost) > 0);
    assert!(lidar.is_scanning());
}

#[test]
fn output_waits_for_the_motor_to_spin_up() {
    let mut lidar = device(RplidarModel::A1, Flower, quiet());
    let out = exchange(&mut lidar, &[0xA5, 0x20], 0.0);
    assert_eq!(out.len(), 7);
    assert!(poll(&mut lidar, 0.499).is_empty());
    assert!(!poll(&mut lidar, 0.6).is_empty());
}

#[test]
fn dtr_stops_the_a1_motor() {
    let mut lidar = device(RplidarModel::A1, Flower, quiet());
    exchange(&mut lidar, &[0xA5, 0x20], 1.0);
    assert!(!run(&mut lidar, 1.0, 2.0).is_empty());
    lidar.set_dtr(true, 2.0);
    assert_eq!(lidar.motor_target_hz(), 0.0);
    assert!(run(&mut lidar, 2.0, 4.0).is_empty());
    assert!(lidar.is_scanning());
    lidar.set_dtr(false, 4.0);
    // The motor stopped by 2.5 s and takes 0.5 s to spin up again.
    assert!(poll(&mut lidar, 4.499).is_empty());
    let resumed = nodes(&poll(&mut lidar, 5.0));
    assert!(!resumed.is_empty() && resumed.iter().all(|n| n.valid));
}

#[test]
fn scan_with_the_motor_stopped_sends_only_the_descriptor() {
    let mut lidar = device(RplidarModel::A1, Flower, quiet());
    lidar.set_dtr(true, 0.0);
    let out = exchange(&mut lidar, &[0xA5, 0x20], 1.0);
    assert_eq!(out.len(), 7);
    assert!(run(&mut lidar, 1.0, 3.0).is_empty());
}

#[test]
fn force_scan_samples_a_stopped_motor_at_one_angle() {
    let mut lidar = device(RplidarModel::A1, Flower, quiet());
    lidar.set_dtr(true, 0.0);
    let out = exchange(&mut lidar, &[0xA5, 0x21], 1.0);
    assert_eq!(out[..7], [0xA5, 0x5A, 0x05, 0x00, 0x00, 0x40, 0x81]);
    let nodes = nodes(&poll(&mut lidar, 1.1));
    assert_eq!(nodes.len(), 200);
    assert!(nodes
        .iter()
        .all(|n| n.valid && !n.start && n.angle_deg == nodes[0].angle_deg));
}

#[test]
fn a2_motor_follows_pwm_and_ignores_dtr() {
    let mut lidar = device(RplidarModel::A2, Flower, quiet());
    exchange(&mut lidar, &[0xA5, 0x20], 1.0);
    lidar.set_dtr(true, 1.2);
    assert_eq!(lidar.motor_target_hz(), 10.0);
    assert!(!poll(&mut lidar, 1.5).is_empty());
    assert!(exchange(&mut lidar, &request(0xF0, &[0, 0]), 1.5).is_empty());
    assert!(lidar.is_scanning());
    assert!(run(&mut lidar, 1.5, 3.0).is_empty());
    exchange(&mut lidar, &request(0xF0, &660u16.to_le_bytes()), 3.0);
    assert!(poll(&mut lidar, 3.499).is_empty());
    assert!(!poll(&mut lidar, 3.6).is_empty());
    // Saturates at 1023.
    exchange(&mut lidar, &request(0xF0, &[0xFF, 0xFF]), 4.0);
    assert_eq!(lidar.motor_target_hz(), 10.0 * 1023.0 / 660.0);
}

#[test]
fn a1_has_no_pwm() {
    let mut lidar = device(RplidarModel::A1, Flower, quiet());
    exchange(&mut lidar, &request(0xF0, &[0, 0]), 1.0);
    assert_eq!(lidar.motor_target_hz(), 5.5);
    assert_eq!(lidar.rejects().get(RejectKind::Unsupported), 1);
}

#[test]
fn reset_reboots_and_prints_the_banner() {
    let mut lidar = device(RplidarModel::A1, Flower, quiet());
    exchange(&mut lidar, &[0xA5, 0x20], 1.0);
    let mut reset_then_health = vec![0xA5, 0x40];
    reset_then_health.extend_from_slice(&[0xA5, 0x52]);
    let before = exchange(&mut lidar, &reset_then_health, 1.5);
    assert_eq!(before.len(), 1000 * 5);
    assert!(!lidar.is_scanning());
    assert_eq!(lidar.rejects().get(RejectKind::WhileRebooting), 2);
    assert!(poll(&mut lidar, 1.5 + BOOT_S / 2.0).is_empty());
    let banner = poll(&mut lidar, 1.5 + BOOT_S);
    assert_eq!(
        banner,
        b"RP LIDAR System.\r\nFirmware Ver 1.29 - rtm, HW Ver 7\r\nModel: 18\r\n"
    );
    assert_eq!(exchange(&mut lidar, &[0xA5, 0x52], 1.6).len(), 10);
}

#[test]
fn protection_stop_refuses_scans() {
    let options = RplidarOptions {
        health: RplidarHealth::Error(7),
        ..quiet()
    };
    let mut lidar = device(RplidarModel::A1, Flower, options);
    assert!(exchange(&mut lidar, &[0xA5, 0x20], 1.0).is_empty());
    assert!(exchange(&mut lidar, &EXPRESS_LEGACY, 1.0).is_empty());
    assert!(!lidar.is_scanning());
    assert_eq!(lidar.rejects().get(RejectKind::ProtectionStop), 2);
    let health = exchange(&mut lidar, &[0xA5, 0x52], 1.0);
    assert_eq!(health[7..], [2, 7, 0]);
}

#[test]
fn nothing_in_range_reads_distance_zero() {
    let mut lidar = device(RplidarModel::A1, Void, quiet());
    let mut out = exchange(&mut lidar, &[0xA5, 0x20], 1.0);
    out.extend(run(&mut lidar, 1.0, 1.2));
    let nodes = nodes(&out[7..]);
    assert!(!nodes.is_empty());
    assert!(nodes
        .iter()
        .all(|n| n.valid && n.distance_mm == 0.0 && n.quality == 0));
}

#[test]
fn dropouts_and_noise_follow_the_options() {
    let options = RplidarOptions {
        dropout: 0.25,
        noise: 0.01,
        angle_compensation: false,
        ..RplidarOptions::default()
    };
    let angles = std::sync::Arc::default();
    let rays = Recorder {
        range: 2.0,
        angles: std::sync::Arc::clone(&angles),
    };
    let mut lidar = device(RplidarModel::A1, rays, options);
    let mut out = exchange(&mut lidar, &[0xA5, 0x20], 1.0);
    out.extend(run(&mut lidar, 1.0, 3.0));
    let nodes = nodes(&out[7..]);
    let lost = nodes.iter().filter(|n| n.distance_mm == 0.0).count() as f64;
    let share = lost / nodes.len() as f64;
    assert!((0.2..0.3).contains(&share), "{share}");
    let ranges: Vec<f64> = nodes
        .iter()
        .map(|n| n.distance_mm)
        .filter(|d| *d > 0.0)
        .collect();
    let mean = ranges.iter().sum::<f64>() / ranges.len() as f64;
    let sd = (ranges.iter().map(|r| (r - mean).powi(2)).sum::<f64>() / ranges.len() as f64).sqrt();
    assert!((mean - 2000.0).abs() < 2.0, "{mean}");
    assert!((15.0..25.0).contains(&sd), "{sd}");
    // Without compensation every sample is one ray, along its node's angle.
    let cast = angles.lock().map(|a| a.len()).unwrap_or(0);
    assert_eq!(cast, nodes.len());
}

// ---- faults ---------------------------------------------------------------

fn faulty(corrupt_every: u64, garbage_every: u64) -> RplidarOptions {
    RplidarOptions {
        faults: Faults {
            corrupt_every,
            garbage_every,
            seed: 9,
        },
        ..quiet()
    }
}

#[test]
fn every_nth_node_has_a_broken_check_bit() {
    let mut lidar = device(RplidarModel::A1, Flower, faulty(7, 0));
    let mut out = exchange(&mut lidar, &[0xA5, 0x20], 1.0);
    out.extend(run(&mut lidar, 1.0, 1.5));
    let nodes = nodes(&out[7..]);
    assert_eq!(nodes.len(), 1000);
    for (i, node) in nodes.iter().enumerate() {
        assert_eq!(node.valid, (i + 1) % 7 != 0, "node {}", i + 1);
    }
}

#[test]
fn every_nth_capsule_has_a_bad_checksum() {
    let mut lidar = device(RplidarModel::A1, Flower, faulty(3, 0));
    let mut out = exchange(&mut lidar, &EXPRESS_LEGACY, 1.0);
    out.extend(run(&mut lidar, 1.0, 1.5));
    let capsules = capsules(&out[7..]);
    assert_eq!(capsules.len(), 62);
    for (i, capsule) in capsules.iter().enumerate() {
        assert_eq!(capsule.checksum_ok, (i + 1) % 3 != 0, "capsule {}", i + 1);
    }
}

#[test]
fn garbage_precedes_every_nth_capsule() {
    let mut lidar = device(RplidarModel::A2, Flower, faulty(0, 4));
    let mut out = exchange(&mut lidar, &request(0x82, &[3, 0, 0, 0, 0]), 1.0);
    out.extend(run(&mut lidar, 1.0, 1.5));
    let found = decode::resync_capsules(&out[7..]);
    assert!(found.len() >= 60, "{}", found.len());
    for (i, (skipped, _)) in found.iter().enumerate() {
        let garbage_expected = (i + 1) % 4 == 0;
        assert_eq!(
            *skipped > 0,
            garbage_expected,
            "capsule {}: {skipped}",
            i + 1
        );
        assert!(*skipped <= 16);
    }
}

#[test]
fn model_names_round_trip() {
    for model in RplidarModel::ALL {
        assert_eq!(RplidarModel::from_name(model.name()), Some(model));
        let lidar = device(model, Void, quiet());
        assert_eq!(lidar.model(), model.name());
        assert_eq!(lidar.uart_baud(), Some(115_200));
    }
    assert_eq!(RplidarModel::from_name("rplidar-a3"), None);
}

#[test]
fn reject_names_are_stable_snake_case() {
    let counts = RejectCounts::default();
    let names: Vec<&str> = counts.iter().map(|(name, _)| name).collect();
    assert_eq!(names.len(), RejectKind::ALL.len());
    assert!(names.contains(&"bad_checksum") && names.contains(&"stalled_host"));
    assert!(names
        .iter()
        .all(|n| n.chars().all(|c| c.is_ascii_lowercase() || c == '_')));
}

// ---- properties -----------------------------------------------------------

fn host_bytes() -> impl Strategy<Value = Vec<u8>> {
    let valid: Vec<Vec<u8>> = vec![
        vec![0xA5, 0x20],
        vec![0xA5, 0x21],
        vec![0xA5, 0x25],
        vec![0xA5, 0x40],
        vec![0xA5, 0x50],
        vec![0xA5, 0x52],
        vec![0xA5, 0x59],
        EXPRESS_LEGACY.to_vec(),
        request(0x82, &[2, 0, 0, 0, 0]),
        request(0x82, &[3, 0, 0, 0, 0]),
        request(0x84, &[0x7F, 0, 0, 0, 1, 0]),
        request(0xF0, &[0, 0]),
        request(0xF0, &[0x58, 0x02]),
        request(0xFF, &[0, 0, 0, 0]),
    ];
    prop_oneof![
        prop::collection::vec(any::<u8>(), 0..64),
        prop::sample::select(valid),
    ]
}

fn step() -> impl Strategy<Value = (Vec<u8>, f64, Option<bool>)> {
    let dt = prop_oneof![9 => 0.0..0.2f64, 1 => Just(30.0)];
    (host_bytes(), dt, prop::option::of(any::<bool>()))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn arbitrary_host_traffic_never_panics_and_output_stays_bounded(
        a2 in any::<bool>(),
        corrupt_every in 0u64..5,
        garbage_every in 0u64..5,
        steps in prop::collection::vec(step(), 1..30),
    ) {
        let model = if a2 { RplidarModel::A2 } else { RplidarModel::A1 };
        let mut lidar = device(model, Flower, faulty(corrupt_every, garbage_every));
        let mut now = 0.0;
        for (bytes, dt, dtr) in steps {
            now += dt;
            lidar.receive(&bytes, now);
            if let Some(asserted) = dtr {
                lidar.set_dtr(asserted, now);
            }
            let out = poll(&mut lidar, now);
            prop_assert!(out.len() <= TX_CAPACITY);
        }
    }

    #[test]
    fn framed_requests_parse_back(cmd in 0x80u8..=0xFF, payload in prop::collection::vec(any::<u8>(), 0..=255)) {
        let mut parser = RequestParser::new();
        let mut rejects = RejectCounts::default();
        let mut parsed = Vec::new();
        for byte in request(cmd, &payload) {
            parsed.extend(parser.push(byte, 0.0, &mut rejects));
        }
        prop_assert_eq!(parsed, vec![Request { cmd, payload }]);
    }

    #[test]
    fn legacy_capsules_decode_back(
        start_q6 in 0u16..23040,
        new_scan in any::<bool>(),
        raw in prop::collection::vec((0u16..=0x3FFF, 0u8..=63), 32),
    ) {
        let mut samples = [LegacySample::default(); 32];
        for (slot, (distance_mm, dtheta_q3)) in samples.iter_mut().zip(&raw) {
            *slot = LegacySample { distance_mm: *distance_mm, dtheta_q3: *dtheta_q3 };
        }
        let bytes = capsule::legacy(start_q6, new_scan, &samples);
        let decoded = decode::capsule(&bytes).expect("framed");
        prop_assert!(decoded.checksum_ok);
        prop_assert_eq!(decoded.new_scan, new_scan);
        prop_assert_eq!(decoded.start_deg, f64::from(start_q6) / 64.0);
        let expected: Vec<(f64, f64)> = raw
            .iter()
            .map(|(d, t)| (f64::from(*d), f64::from(*t) / 8.0))
            .collect();
        prop_assert_eq!(decode::legacy_samples(&decoded), expected);
    }

    #[test]
    fn nodes_decode_back(angle_q6 in 0u16..23040, distance_q2: u16, quality in 0u8..64, start: bool) {
        let node = Node { angle_q6, distance_q2, quality, start };
        let decoded = decode::node(&node.encode(false));
        prop_assert!(decoded.valid);
        prop_assert_eq!(decoded.quality, quality);
        prop_assert_eq!(decoded.start, start);
        prop_assert_eq!(decoded.angle_deg, f64::from(angle_q6) / 64.0);
        prop_assert_eq!(decoded.distance_mm, f64::from(distance_q2) / 4.0);
        prop_assert!(!decode::node(&node.encode(true)).valid);
    }
}
