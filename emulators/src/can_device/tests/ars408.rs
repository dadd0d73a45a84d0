//! ARS408-21 emulator tests.

use super::{frame, run};
use crate::can_device::ars408::frames::cluster_cycle;
use crate::can_device::ars408::scene::Detection;
use crate::can_device::ars408::{OutputType, RadarConfig, CYCLE_PERIOD_S, STATIC_CLUSTERS};
use crate::can_device::{can_emulator, CanDeviceEmulator, CanEmulatorOptions, CanWorld};
use glam::DVec3;
use shroud_drivers::assembly::MountPose;
use shroud_drivers::can::CanFrame;
use shroud_drivers::dbc::{builtin, CanDatabase};
use shroud_sim::MovingSpheres;

fn db() -> CanDatabase {
    builtin("ars408").unwrap()
}

fn radar(options: &CanEmulatorOptions) -> Box<dyn CanDeviceEmulator> {
    can_emulator("ars408", options, CanWorld::default()).unwrap()
}

fn get(db: &CanDatabase, f: &CanFrame, name: &str) -> f64 {
    db.decode(f).unwrap().unwrap().get(name).unwrap()
}

/// A cycle as sent: the status frame and what follows it up to the next
/// status frame (0x201 / 0x700 left out).
struct Cycle {
    start: f64,
    status: CanFrame,
    frames: Vec<(f64, CanFrame)>,
}

fn cycles(frames: &[(f64, CanFrame)], status_id: u32, offset: u32) -> Vec<Cycle> {
    let mut out: Vec<Cycle> = Vec::new();
    for &(t, f) in frames {
        if f.id == 0x201 + offset || f.id == 0x700 + offset {
            continue;
        }
        if f.id == status_id + offset {
            out.push(Cycle {
                start: t,
                status: f,
                frames: Vec::new(),
            });
        } else if let Some(c) = out.last_mut() {
            c.frames.push((t, f));
        }
    }
    out
}

#[test]
fn cluster_general_matches_the_hand_computed_golden_frame() {
    // 701#034FB2048020018A: id 3, 10.0 m long, 0.9 m lat, vrel 0/0, DynProp 1
    // (stationary), RCS 5.0 (sensors.md §2.2, computed by hand). Three nearer
    // clusters take ids 0..2.
    let cluster = |long: f64, lat: f64| Detection {
        long,
        lat,
        vlong: 0.0,
        vlat: 0.0,
        rcs: 5.0,
        moving: false,
    };
    let found = [
        cluster(10.0, 0.9),
        cluster(4.0, 0.0),
        cluster(5.0, 0.0),
        cluster(6.0, 0.0),
    ];
    let config = RadarConfig::default();
    let frames = cluster_cycle(&db(), &config, 0, &found, false).unwrap();
    let general = frames
        .iter()
        .find(|f| f.id == 0x701 && f.data[0] == 3)
        .unwrap();
    assert_eq!(*general, frame(0x701, false, "034FB2048020018A"));
}

#[test]
fn radar_state_matches_hand_computed_bytes() {
    // Default configuration: NVMReadStatus 1 (byte 0 bit 6); MaxDistanceCfg
    // 196 m = raw 98 over byte 1 and the top 2 bits of byte 2 (0x18, 0x80);
    // SortIndex 1 (byte 4 bits 6..4 = 0x10); OutputTypeCfg 2 (byte 5 bits
    // 3..2), SendQuality (bit 4), SendExtInfo (bit 5): 0x38.
    let mut radar = radar(&CanEmulatorOptions::default());
    let frames = run(radar.as_mut(), 0.01);
    let state = frames.iter().find(|(_, f)| f.id == 0x201).unwrap().1;
    assert_eq!(state, frame(0x201, false, "4018800010380000"));
    assert!(
        frames.iter().any(|(_, f)| f.id == 0x700),
        "VersionID at power-up"
    );
}

#[test]
fn a_cluster_cycle_is_status_then_generals_then_qualities_spaced_by_frame_time() {
    let mut radar = radar(&CanEmulatorOptions::default());
    let frames = run(radar.as_mut(), 1.0);
    let db = db();
    let all = cycles(&frames, 0x600, 0);
    assert!(all.len() >= 12, "{} cycles in 1 s", all.len());
    for (k, cycle) in all.iter().enumerate() {
        let near = get(&db, &cycle.status, "NofClustersNear") as usize;
        let far = get(&db, &cycle.status, "NofClustersFar") as usize;
        let n = near + far;
        assert!(n >= 5, "spheres and static clusters seen: {n}");
        assert_eq!(get(&db, &cycle.status, "MeasCounter"), k as f64);
        assert_eq!(cycle.frames.len(), 2 * n, "cycle {k}");
        for (i, (_, f)) in cycle.frames.iter().enumerate() {
            let (id, index) = if i < n { (0x701, i) } else { (0x702, i - n) };
            assert_eq!(f.id, id, "cycle {k} frame {i}");
            assert_eq!(get(&db, f, "ID"), index as f64);
        }
        // 72 ms apart; each frame follows the previous one by its own
        // transmission time at 500 kbit/s (about 0.25 ms for 8 bytes), or
        // more where a 0x201 took the bus.
        let expected_start = (k + 1) as f64 * CYCLE_PERIOD_S;
        assert!(
            (cycle.start - expected_start).abs() < 1e-3,
            "{} vs {expected_start}",
            cycle.start
        );
        let mut previous = cycle.start;
        for &(t, f) in &cycle.frames {
            let gap = t - previous;
            let bits = if f.len == 8 { 111.0 } else { 87.0 };
            assert!(gap >= bits / 500_000.0, "gap {gap}");
            previous = t;
        }
        let first_gap = cycle.frames[0].0 - cycle.start;
        assert!(
            (2.2e-4..=3.0e-4).contains(&first_gap) || first_gap > 3.0e-4,
            "{first_gap}"
        );
    }
    // Sends are in time order.
    assert!(frames.windows(2).all(|w| w[0].0 <= w[1].0));
    // 0x201 every 50 ms: 20 in [0, 1 s].
    let states = frames.iter().filter(|(_, f)| f.id == 0x201).count();
    assert_eq!(states, 20);
}

#[test]
fn quality_off_leaves_out_the_quality_frames() {
    let mut radar = radar(&CanEmulatorOptions::default());
    // SendQuality_valid (byte 0 bit 4) with SendQuality 0.
    radar.receive(&frame(0x200, false, "1000000000000000"), 0.01);
    let frames = run(radar.as_mut(), 0.3);
    assert!(frames.iter().all(|(_, f)| f.id != 0x702));
    assert!(frames.iter().any(|(_, f)| f.id == 0x701));
    let db = db();
    let state = frames.iter().rev().find(|(_, f)| f.id == 0x201).unwrap().1;
    assert_eq!(get(&db, &state, "SendQualityCfg"), 0.0);
}

#[test]
fn configuration_switches_to_objects_and_radar_state_reports_it() {
    let mut radar = radar(&CanEmulatorOptions::default());
    let before = run(radar.as_mut(), 0.1);
    assert!(before.iter().any(|(_, f)| f.id == 0x600));
    // The tier4 README's example: OutputType 1 (objects), SendQuality 1,
    // SendExtInfo 1, SortIndex 1, StoreInNVM 1, each with its valid bit
    // (bytes hand-checked against sensors.md §2.2's bit positions).
    radar.receive(&frame(0x200, false, "F8000000089C0000"), 0.11);
    let after = run(radar.as_mut(), 0.5);
    let db = db();
    let state = after
        .iter()
        .find(|(t, f)| f.id == 0x201 && *t > 0.111)
        .unwrap()
        .1;
    assert_eq!(get(&db, &state, "OutputTypeCfg"), 1.0);
    assert_eq!(get(&db, &state, "SendQualityCfg"), 1.0);
    assert_eq!(get(&db, &state, "SendExtInfoCfg"), 1.0);
    assert_eq!(get(&db, &state, "SortIndex"), 1.0);
    assert_eq!(get(&db, &state, "NVMwriteStatus"), 1.0);
    assert!(after.iter().all(|(_, f)| f.id != 0x600 && f.id != 0x701));
    let all = cycles(&after, 0x60A, 0);
    assert!(all.len() >= 4);
    for cycle in &all {
        let n = get(&db, &cycle.status, "NofObjects") as usize;
        assert_eq!(n, 2, "both spheres tracked");
        let ids: Vec<u32> = cycle.frames.iter().map(|(_, f)| f.id).collect();
        let expected: Vec<u32> = [0x60B, 0x60C, 0x60D]
            .iter()
            .flat_map(|&id| std::iter::repeat_n(id, n))
            .collect();
        assert_eq!(ids, expected);
    }
    assert_eq!(RadarConfig::default().output, OutputType::Clusters);
}

#[test]
fn a_config_frame_for_another_id_is_ignored() {
    let mut radar = radar(&CanEmulatorOptions::default());
    radar.receive(&frame(0x210, false, "0800000008000000"), 0.01);
    radar.receive(&frame(0x200, true, "0800000008000000"), 0.01);
    let frames = run(radar.as_mut(), 0.3);
    assert!(frames.iter().any(|(_, f)| f.id == 0x600));
    assert!(frames.iter().all(|(_, f)| f.id != 0x60A));
}

#[test]
fn sensor_id_moves_every_id_by_0x10() {
    let options = CanEmulatorOptions {
        sensor_id: 1,
        ..CanEmulatorOptions::default()
    };
    let mut radar = radar(&options);
    let frames = run(radar.as_mut(), 0.5);
    let ids: std::collections::BTreeSet<u32> = frames.iter().map(|(_, f)| f.id).collect();
    assert_eq!(
        ids,
        [0x211, 0x610, 0x710, 0x711, 0x712].into_iter().collect()
    );
    let db = db().with_id_offset(0x10).unwrap();
    let state = frames.iter().find(|(_, f)| f.id == 0x211).unwrap().1;
    assert_eq!(get(&db, &state, "SensorID"), 1.0);
    // A frame on the sensor-0 id is someone else's; on 0x210 it is ours:
    // SensorID_valid (byte 0 bit 1) with SensorID 2 (byte 4 bits 2..0).
    radar.receive(&frame(0x200, false, "0200000002000000"), 0.5);
    assert!(run(radar.as_mut(), 0.7)
        .iter()
        .all(|(_, f)| f.id & 0x70 == 0x10));
    radar.receive(&frame(0x210, false, "0200000002000000"), 0.7);
    let moved = run(radar.as_mut(), 1.0);
    let ids: std::collections::BTreeSet<u32> = moved.iter().map(|(_, f)| f.id).collect();
    assert!(
        ids.contains(&0x221) && ids.contains(&0x620) && ids.contains(&0x721),
        "{ids:x?}"
    );
    assert!(ids.iter().all(|id| id & 0x70 == 0x20), "{ids:x?}");
}

#[test]
fn drop_frame_every_removes_exactly_one_general_from_every_nth_cycle() {
    let options = CanEmulatorOptions {
        drop_frame_every: 3,
        ..CanEmulatorOptions::default()
    };
    let mut radar = radar(&options);
    let frames = run(radar.as_mut(), 0.7);
    let db = db();
    let all = cycles(&frames, 0x600, 0);
    assert!(all.len() >= 9);
    for (k, cycle) in all.iter().enumerate() {
        let n = (get(&db, &cycle.status, "NofClustersNear")
            + get(&db, &cycle.status, "NofClustersFar")) as usize;
        let generals: Vec<usize> = cycle
            .frames
            .iter()
            .filter(|(_, f)| f.id == 0x701)
            .map(|(_, f)| get(&db, f, "ID") as usize)
            .collect();
        let qualities = cycle.frames.iter().filter(|(_, f)| f.id == 0x702).count();
        assert_eq!(qualities, n);
        if (k + 1) % 3 == 0 {
            assert_eq!(generals.len(), n - 1, "cycle {k}");
            assert!(!generals.contains(&(n / 2)));
        } else {
            assert_eq!(generals, (0..n).collect::<Vec<_>>(), "cycle {k}");
        }
    }
}

/// The sphere centres and velocities in the radar frame of the default
/// mount (10 m behind the origin, 0.5 m up, not rotated).
fn truth(t: f64) -> [(DVec3, DVec3); 2] {
    let spheres = MovingSpheres::default();
    let mount = CanEmulatorOptions::default().radar_mount.translation;
    let h = 1e-4;
    let [a0, a1] = spheres.centres(t - h);
    let [c0, c1] = spheres.centres(t);
    let [b0, b1] = spheres.centres(t + h);
    let v = |a: [f64; 3], b: [f64; 3]| (DVec3::from_array(b) - DVec3::from_array(a)) / (2.0 * h);
    [
        (DVec3::from_array(c0) - mount, v(a0, b0)),
        (DVec3::from_array(c1) - mount, v(a1, b1)),
    ]
}

#[test]
fn objects_follow_the_moving_spheres() {
    let mut radar = radar(&CanEmulatorOptions::default());
    radar.receive(&frame(0x200, false, "0800000008000000"), 0.0);
    let frames = run(radar.as_mut(), 4.0);
    let db = db();
    let mut positions = Vec::new();
    let mut fastest: f64 = 0.0;
    for cycle in cycles(&frames, 0x60A, 0) {
        // The cycle was measured when it started (its 0x60A was queued at
        // a multiple of the period).
        let t = (cycle.start / CYCLE_PERIOD_S).floor() * CYCLE_PERIOD_S;
        let truth = truth(t);
        for (_, f) in cycle.frames.iter().filter(|(_, f)| f.id == 0x60B) {
            let id = get(&db, f, "ID") as usize;
            let (centre, velocity) = truth[id];
            let long = get(&db, f, "DistLong");
            let lat = get(&db, f, "DistLat");
            let vlong = get(&db, f, "VrelLong");
            let vlat = get(&db, f, "VrelLat");
            // 0.2 m steps and 3 cm noise; 0.25 m/s steps and 3 cm/s noise.
            assert!((long - centre.x).abs() < 0.25, "{long} vs {}", centre.x);
            assert!((lat - centre.y).abs() < 0.25, "{lat} vs {}", centre.y);
            assert!(
                (vlong - velocity.x).abs() < 0.26,
                "{vlong} vs {}",
                velocity.x
            );
            assert!((vlat - velocity.y).abs() < 0.26, "{vlat} vs {}", velocity.y);
            let moving = velocity.truncate().length() >= 0.05;
            assert_eq!(get(&db, f, "DynProp"), if moving { 0.0 } else { 1.0 });
            fastest = fastest.max(vlong.hypot(vlat));
            positions.push((id, long, lat));
        }
    }
    assert!(fastest >= 0.5, "the orbiting sphere moves: {fastest}");
    let orbit: Vec<f64> = positions.iter().filter(|p| p.0 == 1).map(|p| p.1).collect();
    let spread = orbit.iter().cloned().fold(f64::MIN, f64::max)
        - orbit.iter().cloned().fold(f64::MAX, f64::min);
    assert!(spread > 1.0, "positions change: {spread}");
}

#[test]
fn clusters_lie_on_the_spheres_near_sides_and_on_the_static_wall() {
    let mut radar = radar(&CanEmulatorOptions::default());
    let frames = run(radar.as_mut(), 3.0);
    let db = db();
    let mut moving_seen = false;
    for cycle in cycles(&frames, 0x600, 0) {
        let t = (cycle.start / CYCLE_PERIOD_S).floor() * CYCLE_PERIOD_S;
        let spheres = truth(t);
        let radii = MovingSpheres::default().radii.map(f64::from);
        let mut walls = 0;
        for (_, f) in cycle.frames.iter().filter(|(_, f)| f.id == 0x701) {
            let p = glam::DVec2::new(get(&db, f, "DistLong"), get(&db, f, "DistLat"));
            let on_sphere = spheres.iter().zip(radii).any(|((c, _), r)| {
                let gap = (p - c.truncate()).length() - r;
                gap.abs() < 0.3 && p.x < c.x + 0.3 // the near side
            });
            let on_wall = STATIC_CLUSTERS
                .iter()
                .any(|s| (p.x - s[0]).abs() < 0.3 && (p.y - s[1]).abs() < 0.3);
            assert!(on_sphere || on_wall, "{p}");
            if on_wall && !on_sphere {
                walls += 1;
                assert_eq!(get(&db, f, "DynProp"), 1.0);
                assert_eq!(get(&db, f, "VrelLong"), 0.0);
            }
            let v = get(&db, f, "VrelLong").hypot(get(&db, f, "VrelLat"));
            if get(&db, f, "DynProp") == 0.0 && v >= 0.25 {
                moving_seen = true;
            }
        }
        assert_eq!(walls, STATIC_CLUSTERS.len());
    }
    assert!(moving_seen);
}

#[test]
fn a_radar_turned_away_sees_only_its_static_clusters() {
    let options = CanEmulatorOptions {
        radar_mount: MountPose::from_xyz_rpy([-10.0, 0.0, 0.5], [0.0, 0.0, std::f64::consts::PI]),
        ..CanEmulatorOptions::default()
    };
    let mut radar = radar(&options);
    let frames = run(radar.as_mut(), 0.2);
    let db = db();
    for cycle in cycles(&frames, 0x600, 0) {
        let n =
            get(&db, &cycle.status, "NofClustersNear") + get(&db, &cycle.status, "NofClustersFar");
        assert_eq!(n as usize, STATIC_CLUSTERS.len());
    }
}

#[test]
fn max_distance_is_clamped_to_the_radars_limits_and_limits_the_clusters() {
    let mut radar = radar(&CanEmulatorOptions::default());
    // MaxDistance_valid (byte 0 bit 0), MaxDistance 20 m = raw 10: byte 1 =
    // 10 >> 2 = 0x02, byte 2 = (10 & 3) << 6 = 0x80. Below a standard-range
    // unit's 196 m: it takes 196 m, and says so.
    radar.receive(&frame(0x200, false, "0102800000000000"), 0.0);
    let frames = run(radar.as_mut(), 0.3);
    let db = db();
    let state = frames.iter().rev().find(|(_, f)| f.id == 0x201).unwrap().1;
    assert_eq!(get(&db, &state, "MaxDistanceCfg"), 196.0);
    // 300 m = raw 150: byte 1 = 150 >> 2 = 0x25, byte 2 = (150 & 3) << 6 = 0x80.
    radar.receive(&frame(0x200, false, "0125800000000000"), 0.3);
    let frames = run(radar.as_mut(), 0.6);
    let state = frames.iter().rev().find(|(_, f)| f.id == 0x201).unwrap().1;
    assert_eq!(get(&db, &state, "MaxDistanceCfg"), 260.0);
    for (_, f) in frames.iter().filter(|(_, f)| f.id == 0x701) {
        assert!(get(&db, f, "DistLong") < 260.5);
    }
}

#[test]
fn long_silence_is_skipped_not_replayed() {
    let mut radar = radar(&CanEmulatorOptions::default());
    let mut frames = Vec::new();
    radar.poll(3600.0, &mut frames);
    // At most the last second's worth (~14 cycles of ≤ 40 frames, 20 states).
    assert!(frames.len() < 1000, "{}", frames.len());
    assert!(frames.iter().all(|(t, _)| *t >= 3598.0));
}
