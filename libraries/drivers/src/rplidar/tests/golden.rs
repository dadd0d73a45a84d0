//! Golden vectors: bytes from the protocol PDF and the research notes §1.2,
//! and hand-computed capsules.

use super::sim::*;
use crate::device::DeviceStats;
use crate::rplidar::angle::rep103;
use crate::rplidar::capsule::CapsuleStream;
use crate::rplidar::dense::DenseLayout;
use crate::rplidar::descriptor::{Descriptor, DescriptorError, SendMode};
use crate::rplidar::express::ExpressLayout;
use crate::rplidar::node::{valid_first, valid_second, Node};
use crate::rplidar::replies::{DeviceInfo, Health, HealthStatus, SampleRate};
use crate::rplidar::request;
use crate::rplidar::stream::{Sample, StreamEvent};

#[test]
fn standard_node_3d_41_2d_49_13() {
    let bytes = [0x3D, 0x41, 0x2D, 0x49, 0x13];
    assert!(valid_first(bytes[0]) && valid_second(bytes[1]));
    let node = Node::parse(bytes);
    assert_eq!(node.quality, 15);
    assert!(node.start);
    assert_eq!(f64::from(node.angle_q6) / 64.0, 90.5);
    assert_eq!(f64::from(node.distance_q2) / 4.0, 1234.25);
}

#[test]
fn standard_node_through_the_decoder_becomes_a_rep103_ray() {
    // Two revolution boundaries around the golden node so it leaves in a
    // scan, and 8 nodes after the second to confirm it.
    let mut stream = node(1, true, 0, 4).to_vec();
    stream.extend([0x3D ^ 0x03, 0x41, 0x2D, 0x49, 0x13]); // same node, S cleared
    stream.extend(node(1, true, 0, 4));
    for k in 1..=8 {
        stream.extend(node(1, false, k, 4));
    }
    let (revs, _) = decode(crate::rplidar::stream::SampleFormat::Standard, &[&stream]);
    assert_eq!(revs.len(), 1);
    let ray = revs[0].rays[1];
    // 90.5° clockwise = −90.5° in REP-103.
    assert!((ray.angle - (-90.5f32).to_radians()).abs() < 1e-6);
    assert_eq!(ray.range, 1.23425);
    assert_eq!(ray.intensity, Some(15.0));
}

#[test]
fn legacy_express_request() {
    assert_eq!(
        request::express_scan(0),
        [0xA5, 0x82, 0x05, 0x00, 0x00, 0x00, 0x00, 0x00, 0x22]
    );
}

#[test]
fn bare_and_payload_requests() {
    assert_eq!(request::encode(0x25, &[]), [0xA5, 0x25]);
    assert_eq!(
        request::encode(0x52, &[1, 2]),
        [0xA5, 0x52],
        "no payload room"
    );
    // A5 ^ F0 ^ 02 ^ 94 ^ 02 = 0xC1 (660 = 0x0294).
    assert_eq!(
        request::motor(0xF0, 660),
        [0xA5, 0xF0, 0x02, 0x94, 0x02, 0xC1]
    );
    // A5 ^ FF ^ 04 = 0x5E.
    assert_eq!(
        request::acc_board_flag(),
        [0xA5, 0xFF, 0x04, 0, 0, 0, 0, 0x5E]
    );
    // A5 ^ 84 ^ 06 ^ 71 ^ 01 = 0x57 (key 0x71, mode 1).
    assert_eq!(
        request::lidar_conf(0x71, Some(1)),
        [0xA5, 0x84, 0x06, 0x71, 0, 0, 0, 0x01, 0x00, 0x57]
    );
}

fn parse(bytes: [u8; 7]) -> Descriptor {
    Descriptor::parse(&bytes).unwrap()
}

#[test]
fn descriptors() {
    let health = parse([0xA5, 0x5A, 0x03, 0x00, 0x00, 0x00, 0x06]);
    assert_eq!(
        (health.len, health.mode, health.answer_type),
        (3, SendMode::Single, 0x06)
    );
    let info = parse([0xA5, 0x5A, 0x14, 0x00, 0x00, 0x00, 0x04]);
    assert_eq!(
        (info.len, info.mode, info.answer_type),
        (20, SendMode::Single, 0x04)
    );
    let scan = parse([0xA5, 0x5A, 0x05, 0x00, 0x00, 0x40, 0x81]);
    assert_eq!(
        (scan.len, scan.mode, scan.answer_type),
        (5, SendMode::Multiple, 0x81)
    );
    let express = parse([0xA5, 0x5A, 0x54, 0x00, 0x00, 0x40, 0x82]);
    assert_eq!(
        (express.len, express.mode, express.answer_type),
        (84, SendMode::Multiple, 0x82)
    );
    assert_eq!(
        Descriptor::parse(&[0xA5, 0x5A, 0, 0, 0, 0x80, 0x81]),
        Err(DescriptorError::BadMode(2))
    );
    assert_eq!(
        Descriptor::parse(&[0xA5, 0x5B, 0, 0, 0, 0, 0]),
        Err(DescriptorError::BadSync)
    );
}

#[test]
fn info_health_samplerate_payloads() {
    let info = DeviceInfo::parse(&info_payload(0x18, 1, 29, 7)).unwrap();
    assert_eq!(info.model_name(), "A1M8");
    assert_eq!(info.firmware(), 0x011D);
    assert_eq!(info.firmware_text(), "1.29");
    assert_eq!(info.hardware, 7);
    assert_eq!(info.serial_hex(), "000102030405060708090A0B0C0D0E0F");
    assert!(info.supports_lidar_conf());
    assert!(DeviceInfo::parse(&[0; 19]).is_err());
    let s1 = DeviceInfo::parse(&info_payload(0x61, 1, 2, 18)).unwrap();
    assert_eq!(s1.model_name(), "S1M1");
    assert!(s1.has_builtin_motor_control());

    let h = Health::parse(&[2, 0x34, 0x12]).unwrap();
    assert_eq!((h.status, h.error_code), (HealthStatus::Error, 0x1234));
    assert_eq!(
        Health::parse(&[1, 0, 0]).unwrap().status,
        HealthStatus::Warning
    );
    assert_eq!(
        Health::parse(&[9, 0, 0]).unwrap().status,
        HealthStatus::Unknown(9)
    );
    assert!(Health::parse(&[0, 0]).is_err());

    let r = SampleRate::parse(&[0xFC, 0x01, 0xFE, 0x00]).unwrap();
    assert_eq!((r.standard_us, r.express_us), (508, 254));
}

fn samples(events: &[StreamEvent]) -> Vec<Sample> {
    events
        .iter()
        .filter_map(|e| match e {
            StreamEvent::Sample(s) => Some(*s),
            _ => None,
        })
        .collect()
}

#[test]
fn express_capsule_by_hand() {
    // Capsule A starts at 10.0° (q6 640), capsule B at 12.0° (q6 768):
    // span = 2.0°, so sample k's raw angle is 10 + k · 2/32 = 10 + k · 0.0625°.
    // Cabin 0: sample 0 = 1000 mm (q2 4000), dθ = 0x13 q3 = 2.375°;
    //          sample 1 = 2000 mm (q2 8000), dθ = 0x08 q3 = 1.0°.
    // heading 0 = 10 − 2.375 = 7.625°; heading 1 = 10.0625 − 1.0 = 9.0625°.
    // Other samples: distance 0, dθ 0 → heading 10 + k · 0.0625 (k = 31: 11.9375°).
    let mut cabins = [(0u16, 0u8); 32];
    cabins[0] = (4000, 0x13);
    cabins[1] = (8000, 0x08);
    let a = express_capsule(640, true, &cabins);
    let b = express_capsule(768, false, &[(0, 0); 32]);
    // Wire bytes of cabin 0: 4000 | (0x13 >> 4) = 0x0FA1; 8000 = 0x1F40;
    // offsets = 0x3 | 0x8 << 4 = 0x83.
    assert_eq!(a[4..9], [0xA1, 0x0F, 0x40, 0x1F, 0x83]);
    assert_eq!(a[2..4], [0x80, 0x82], "640 | S = 0x8280");

    let mut stream = CapsuleStream::<ExpressLayout>::new(clock());
    let (mut stats, mut events) = (DeviceStats::default(), Vec::new());
    stream.feed(&a, t(0), &mut stats, &mut events);
    assert_eq!(events, [StreamEvent::Restart], "A waits for B");
    stream.feed(&b, t(0), &mut stats, &mut events);
    let s = samples(&events);
    assert_eq!(s.len(), 32);
    assert_eq!(s[0].heading_q16, 499_712); // 7.625 · 65536
    assert_eq!(s[0].distance_q2, 4000);
    assert_eq!(s[1].heading_q16, 593_920); // 9.0625 · 65536
    assert_eq!(s[1].distance_q2, 8000);
    assert_eq!(s[2].heading_q16, 663_552); // 10.125 · 65536
    assert_eq!(s[31].heading_q16, 782_336); // 11.9375 · 65536
    assert_eq!(s[31].distance_q2, 0);
    assert!(s
        .iter()
        .all(|x| !x.starts_revolution && x.quality.is_none()));
    assert_eq!(stats.total_errors(), 0);
    // Ray angles: −7.625° → −0.133081 rad.
    assert!((rep103(s[0].heading_q16) - (-0.133_081_35)).abs() < 1e-6);
}

#[test]
fn express_revolution_boundary_where_the_raw_angle_wraps() {
    // A at 359.0° (q6 22976), B at 1.0° (q6 64): span = 2.0° (+360),
    // raw angle 359 + k · 0.0625 passes 360 at k = 16 → sample 16 starts a
    // revolution (its raw angle, 0.0°, is smaller than sample 15's 359.9375°).
    let a = express_capsule(22_976, false, &[(400, 0); 32]);
    let b = express_capsule(64, false, &[(400, 0); 32]);
    let mut stream = CapsuleStream::<ExpressLayout>::new(clock());
    let (mut stats, mut events) = (DeviceStats::default(), Vec::new());
    stream.feed(&[a, b].concat(), t(0), &mut stats, &mut events);
    let s = samples(&events);
    let starts: Vec<usize> = (0..32).filter(|&k| s[k].starts_revolution).collect();
    assert_eq!(starts, [16]);
    assert_eq!(s[16].heading_q16, 360 << 16, "unwrapped; rep103 wraps it");
    assert_eq!(rep103(s[16].heading_q16), 0.0);
}

#[test]
fn dense_capsule_by_hand() {
    // A at 20.0° (q6 1280), B at 22.0° (q6 1408): span q8 = 128 << 2 = 512;
    // step q16 = (512 << 8) / 40 = 3276 (truncated from 3276.8, as the SDK).
    // Sample k heading q16 = 20 · 65536 + 3276 k = 1_310_720 + 3276 k;
    // k = 39: 1_438_484 (21.9495°). Distances are mm: 1500 mm → q2 6000.
    let mut d = [0u16; 40];
    d[0] = 1500;
    d[39] = 65535;
    let a = dense_capsule(1280, false, &d);
    let b = dense_capsule(1408, false, &[0; 40]);
    let mut stream = CapsuleStream::<DenseLayout>::new(clock());
    let (mut stats, mut events) = (DeviceStats::default(), Vec::new());
    stream.feed(&[a, b].concat(), t(0), &mut stats, &mut events);
    let s = samples(&events);
    assert_eq!(s.len(), 40);
    assert_eq!((s[0].heading_q16, s[0].distance_q2), (1_310_720, 6000));
    assert_eq!((s[1].heading_q16, s[1].distance_q2), (1_313_996, 0));
    assert_eq!((s[39].heading_q16, s[39].distance_q2), (1_438_484, 262_140));
    assert_eq!(stats.total_errors(), 0);
}

#[test]
fn rep103_angles() {
    let deg = |d: i64| rep103(d << 16);
    assert_eq!(deg(0), 0.0);
    assert!(
        (deg(90) + std::f32::consts::FRAC_PI_2).abs() < 1e-6,
        "90° cw = −π/2"
    );
    assert_eq!(deg(180), std::f32::consts::PI, "−π wraps to +π");
    assert!((deg(270) - std::f32::consts::FRAC_PI_2).abs() < 1e-6);
    assert_eq!(deg(360), 0.0);
    for q in (0..(360 << 16)).step_by(9973) {
        let a = rep103(q);
        assert!(
            a > -std::f32::consts::PI && a <= std::f32::consts::PI,
            "{q}"
        );
    }
}
