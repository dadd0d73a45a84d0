//! Tests of the scan-to-cloud assembly: poses, profiles, joint tracks, windows.

use super::*;
use crate::device::{HostTime, RangeScan, Ray, StampBound};
use glam::DVec3;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

const MS: u64 = 1_000_000;
const T0: u64 = 1_700_000_000_000_000_000;

fn ray(angle: f32, range: f32, offset_ns: u32) -> Ray {
    Ray {
        angle,
        range,
        intensity: None,
        offset_ns,
    }
}

fn scan(sequence: u32, stamp_ns: u64, rays: Vec<Ray>) -> RangeScan {
    RangeScan {
        sequence,
        stamp_ns,
        received: HostTime::new(stamp_ns - T0 + 1_000, stamp_ns),
        rays,
        stamp_bound: StampBound::Untracked,
    }
}

fn close(a: [f32; 3], b: [f64; 3]) -> bool {
    a.iter().zip(b).all(|(x, y)| (*x as f64 - y).abs() < 1e-5)
}

#[test]
fn a_mount_pose_parses_metres_and_degrees_and_applies_rpy() {
    let pose: MountPose = "1,2,3,0,0,90".parse().unwrap();
    let p = pose.apply(DVec3::X);
    assert!((p - DVec3::new(1.0, 3.0, 3.0)).length() < 1e-12, "{p}");
    // Pitch 90°: forward (x) turns to down (-z), REP-103's right-hand rule about y.
    let pitch: MountPose = "0,0,0,0,90,0".parse().unwrap();
    assert!((pitch.apply(DVec3::X) - DVec3::new(0.0, 0.0, -1.0)).length() < 1e-12);
    for bad in ["1,2,3", "1,2,3,4,5,x", "1,2,3,4,5,inf", ""] {
        assert!(bad.parse::<MountPose>().is_err(), "{bad}");
    }
}

#[test]
fn a_fixed_mount_places_rays_in_the_robot_frame_and_skips_invalid_ones() {
    let mount = MovingMount::fixed("1,0,0.5,0,0,90".parse().unwrap());
    let mut assembler = CloudAssembler::new(AssemblyConfig::fixed(mount)).unwrap();
    let rays = vec![
        ray(0.0, 2.0, 0),
        ray(std::f32::consts::FRAC_PI_2, 1.0, 10),
        ray(0.3, f32::NAN, 20),
    ];
    let mut out = Vec::new();
    assembler.push_scan(scan(0, T0, rays), &mut out);
    assert_eq!(out.len(), 1);
    let cloud = &out[0].cloud;
    assert_eq!(cloud.stamp_ns, T0);
    assert_eq!(cloud.points.len(), 2);
    // Yaw 90°: sensor +x is robot +y, sensor +y is robot -x.
    assert!(
        close(cloud.points[0], [1.0, 2.0, 0.5]),
        "{:?}",
        cloud.points
    );
    assert!(
        close(cloud.points[1], [0.0, 0.0, 0.5]),
        "{:?}",
        cloud.points
    );
    assert_eq!(assembler.stats().invalid_rays, 1);
    assert!(cloud.intensity.is_none());
}

#[test]
fn intensity_is_kept_when_every_ray_has_it() {
    let mount = MovingMount::fixed(MountPose::default());
    let mut assembler = CloudAssembler::new(AssemblyConfig::fixed(mount)).unwrap();
    let mut rays = vec![ray(0.0, 1.0, 0), ray(0.1, 1.0, 5)];
    rays[0].intensity = Some(7.0);
    rays[1].intensity = Some(9.0);
    let mut out = Vec::new();
    assembler.push_scan(scan(0, T0, rays), &mut out);
    assert_eq!(out[0].cloud.intensity, Some(vec![7.0, 9.0]));
}

#[test]
fn sweep_profiles_have_the_documented_angles_and_sweep_boundaries() {
    let sine: SweepProfile = "sine:30:2".parse().unwrap();
    let at = |p: &SweepProfile, s: f64| p.angle_at((s * 1e9) as u64);
    assert!(at(&sine, 0.0).abs() < 1e-12);
    assert!((at(&sine, 0.5) - 30f64.to_radians()).abs() < 1e-9);
    // Sweeps change at the extremes (0.5 s and 1.5 s into each 2 s period).
    let idx = |p: &SweepProfile, s: f64| p.sweep_index((s * 1e9) as u64);
    assert_eq!(idx(&sine, 0.49), idx(&sine, 0.0));
    assert_eq!(idx(&sine, 0.51), idx(&sine, 0.0) + 1);
    assert_eq!(idx(&sine, 1.49), idx(&sine, 0.51));
    assert_eq!(idx(&sine, 1.51), idx(&sine, 0.51) + 1);
    let tri: SweepProfile = "triangle:20:4:-10".parse().unwrap();
    assert!((at(&tri, 0.0) - (-30f64).to_radians()).abs() < 1e-9);
    assert!((at(&tri, 1.0) - (-10f64).to_radians()).abs() < 1e-9);
    assert!((at(&tri, 2.0) - 10f64.to_radians()).abs() < 1e-9);
    assert_eq!(idx(&tri, 1.99) + 1, idx(&tri, 2.01));
    let rot: SweepProfile = "rotate:0.5".parse().unwrap();
    assert!((at(&rot, 0.125) - FRAC_PI_2).abs() < 1e-9);
    assert_eq!(idx(&rot, 0.49) + 1, idx(&rot, 0.51));
    assert!((rot.max_speed() - 4.0 * PI).abs() < 1e-9);
    for bad in [
        "sine:30",
        "sine:0:1",
        "sine:200:1",
        "sine:30:0",
        "sine:30:nan",
        "wobble:1:2",
        "rotate:1:2",
        "triangle:10:1:2:3",
    ] {
        assert!(bad.parse::<SweepProfile>().is_err(), "{bad}");
    }
}

#[test]
fn cloud_windows_parse_and_refuse_nonsense() {
    assert_eq!("sweep".parse(), Ok(CloudWindow::Sweep));
    assert_eq!("scans:5".parse(), Ok(CloudWindow::Scans(5)));
    assert_eq!("time:0.25".parse(), Ok(CloudWindow::Time(250 * MS)));
    for bad in ["scans:0", "scans:x", "time:0", "time:-1", "sweeps", ""] {
        assert!(bad.parse::<CloudWindow>().is_err(), "{bad}");
    }
    let fixed = AssemblyConfig {
        window: CloudWindow::Sweep,
        ..AssemblyConfig::fixed(MovingMount::fixed(MountPose::default()))
    };
    assert!(CloudAssembler::new(fixed).is_err());
}

fn tilting(profile: &str, window: CloudWindow) -> CloudAssembler {
    let mount = MovingMount {
        base: "0,0,1,0,0,0".parse().unwrap(),
        axis: DVec3::Y,
        sensor: MountPose::default(),
        motion: MountMotion::Profile(profile.parse().unwrap()),
    };
    CloudAssembler::new(AssemblyConfig {
        window,
        ..AssemblyConfig::fixed(mount)
    })
    .unwrap()
}

#[test]
fn each_ray_is_placed_at_the_tilt_of_its_own_time() {
    let mut assembler = tilting("triangle:45:4", CloudWindow::Scans(1));
    // Epoch-aligned: T0 is a multiple of 4 s, so the tilt is -45° at T0 and
    // rises 45° a second.
    assert_eq!(T0 % 4_000_000_000, 0);
    let rays = vec![ray(0.0, 1.0, 0), ray(0.0, 1.0, 500_000_000)];
    let mut out = Vec::new();
    assembler.push_scan(scan(0, T0, rays), &mut out);
    let points = &out[0].cloud.points;
    // Tilt -45° about +y lifts forward rays: (cos 45, 0, sin 45) + 1 m up.
    let s = 45f64.to_radians().sin();
    assert!(close(points[0], [s, 0.0, 1.0 + s]), "{points:?}");
    let t = (-22.5f64).to_radians();
    assert!(
        close(points[1], [t.cos(), 0.0, 1.0 - t.sin()]),
        "{points:?}"
    );
}

#[test]
fn a_cloud_per_sweep_is_cut_at_the_sweep_boundary_inside_a_scan() {
    let mut assembler = tilting("triangle:45:4", CloudWindow::Sweep);
    let mut out = Vec::new();
    // 10 scans of 0.25 s, 5 rays each, from T0 + 1 s: the boundary at T0 + 2 s
    // falls at the start of the 5th scan; the next at T0 + 4 s is not reached.
    for k in 0..10u32 {
        let rays = (0..5).map(|i| ray(0.0, 1.0, i * 50 * MS as u32)).collect();
        let stamp = T0 + 1_000 * MS + k as u64 * 250 * MS;
        assembler.push_scan(scan(k, stamp, rays), &mut out);
    }
    assert_eq!(out.len(), 1, "one sweep completed");
    assert_eq!(out[0].cloud.points.len(), 20);
    assert_eq!(out[0].scans, 4);
    assert_eq!(out[0].cloud.stamp_ns, T0 + 1_000 * MS);
    // Its age counts from its first scan's arrival, not its last's.
    assert_eq!(
        out[0].first_received,
        HostTime::new(1_000 * MS + 1_000, T0 + 1_000 * MS)
    );
    assert_eq!(out[0].last_received.unix_ns, T0 + 1_750 * MS);
}

#[test]
fn scan_and_time_windows_group_as_configured() {
    let fixed = || MovingMount::fixed(MountPose::default());
    let mut three = CloudAssembler::new(AssemblyConfig {
        window: CloudWindow::Scans(3),
        ..AssemblyConfig::fixed(fixed())
    })
    .unwrap();
    let mut out = Vec::new();
    for k in 0..7u32 {
        three.push_scan(
            scan(k, T0 + k as u64 * MS, vec![ray(0.0, 1.0, 0)]),
            &mut out,
        );
    }
    assert_eq!(out.iter().map(|c| c.scans).collect::<Vec<_>>(), [3, 3]);
    let mut windowed = CloudAssembler::new(AssemblyConfig {
        window: CloudWindow::Time(10 * MS),
        ..AssemblyConfig::fixed(fixed())
    })
    .unwrap();
    out.clear();
    for k in 0..25u64 {
        windowed.push_scan(
            scan(k as u32, T0 + k * MS, vec![ray(0.0, 1.0, 0)]),
            &mut out,
        );
    }
    assert_eq!(out.iter().map(|c| c.scans).collect::<Vec<_>>(), [10, 10]);
}

fn joint_mount() -> MovingMount {
    MovingMount {
        base: MountPose::default(),
        axis: DVec3::Z,
        sensor: MountPose::default(),
        motion: MountMotion::Joint { name: "pan".into() },
    }
}

fn on_joint() -> CloudAssembler {
    CloudAssembler::new(AssemblyConfig::fixed(joint_mount())).unwrap()
}

#[test]
fn a_joint_mount_waits_for_samples_covering_the_whole_scan() {
    let mut assembler = on_joint();
    let mut out = Vec::new();
    assembler.push_joint(T0, 0.0, &mut out);
    let rays = vec![ray(0.0, 1.0, 0), ray(0.0, 1.0, 10 * MS as u32)];
    assembler.push_scan(scan(0, T0 + 5 * MS, rays), &mut out);
    assert!(out.is_empty(), "the last ray is not covered yet");
    assembler.push_joint(T0 + 20 * MS, FRAC_PI_2, &mut out);
    assert_eq!(out.len(), 1);
    let p = &out[0].cloud.points;
    // 5 ms and 15 ms into a 0..π/2 pan over 20 ms: π/8 and 3π/8.
    let a = PI / 8.0;
    let b = 3.0 * PI / 8.0;
    assert!(close(p[0], [a.cos(), a.sin(), 0.0]), "{p:?}");
    assert!(close(p[1], [b.cos(), b.sin(), 0.0]), "{p:?}");
}

#[test]
fn scans_the_joint_samples_cannot_cover_are_dropped_and_counted() {
    let mut assembler = on_joint();
    let mut out = Vec::new();
    assembler.push_joint(T0 + 100 * MS, 0.0, &mut out);
    // Older than every sample: lost.
    assembler.push_scan(scan(0, T0, vec![ray(0.0, 1.0, 0)]), &mut out);
    assert_eq!(assembler.stats().mount_angle_missing, 1);
    // Across a gap longer than the limit (200 ms): lost.
    assembler.push_scan(scan(1, T0 + 300 * MS, vec![ray(0.0, 1.0, 0)]), &mut out);
    assembler.push_joint(T0 + 600 * MS, 0.1, &mut out);
    assert_eq!(assembler.stats().mount_angle_missing, 2);
    // Waiting too long: expired.
    assembler.push_scan(scan(2, T0 + 700 * MS, vec![ray(0.0, 1.0, 0)]), &mut out);
    let received = HostTime::new(700 * MS + 1_000, T0 + 700 * MS);
    assembler.expire(received.plus_ns(400 * MS), &mut out);
    assert_eq!(assembler.stats().mount_angle_missing, 2);
    assembler.expire(received.plus_ns(600 * MS), &mut out);
    assert_eq!(assembler.stats().mount_angle_missing, 3);
    assert!(out.is_empty());
    // Refused samples are counted.
    assembler.push_joint(T0, 0.0, &mut out);
    assembler.push_joint(T0 + 900 * MS, f64::NAN, &mut out);
    assert_eq!(assembler.stats().joint_samples_refused, 2);
}

#[test]
fn a_joint_track_counts_sweeps_at_reversals_and_full_turns() {
    let mut nod = JointTrack::new(u64::MAX);
    for (k, a) in [0.0, 0.2, 0.4, 0.3, 0.1, 0.2].iter().enumerate() {
        assert!(nod.push(k as u64 * MS, *a));
    }
    let sweeps: Vec<u64> = (0..6).map(|k| nod.at(k * MS).unwrap().1).collect();
    assert_eq!(sweeps, [0, 0, 0, 1, 1, 2]);
    let mut turn = JointTrack::new(u64::MAX);
    // A continuous joint reported wrapped to (-π, π]: unwrapped across ±π.
    let mut angle: f64 = 0.0;
    for k in 0..40u64 {
        let wrapped = (angle + PI).rem_euclid(TAU) - PI;
        assert!(turn.push(k * MS, wrapped));
        angle += 0.4;
    }
    let (a, sweep) = turn.at(39 * MS).unwrap();
    assert!((a - 39.0 * 0.4).abs() < 1e-9, "{a}");
    assert_eq!(sweep, (39.0 * 0.4 / TAU).floor() as u64);
    assert!(turn.at(40 * MS).is_none(), "never extrapolated");
}

#[test]
fn a_flush_completes_the_cloud_once_the_scans_waiting_at_it_are_through() {
    let mut assembler = CloudAssembler::new(AssemblyConfig {
        window: CloudWindow::Time(10_000 * MS),
        ..AssemblyConfig::fixed(joint_mount())
    })
    .unwrap();
    let mut out = Vec::new();
    assembler.push_joint(T0, 0.0, &mut out);
    assembler.push_joint(T0 + 10 * MS, 0.0, &mut out);
    assembler.push_scan(scan(0, T0 + 5 * MS, vec![ray(0.0, 1.0, 0)]), &mut out);
    // Waits for samples after its last ray.
    assembler.push_scan(scan(1, T0 + 20 * MS, vec![ray(0.0, 1.0, 0)]), &mut out);
    assembler.flush(&mut out);
    assert!(out.is_empty(), "scan 1 still belongs to the flushed cloud");
    assembler.push_joint(T0 + 30 * MS, 0.0, &mut out);
    assert_eq!(out.len(), 1);
    assert_eq!(out[0].scans, 2);
    // The next scan starts a new cloud.
    assembler.push_scan(scan(2, T0 + 25 * MS, vec![ray(0.0, 1.0, 0)]), &mut out);
    assembler.flush(&mut out);
    assert_eq!(out.len(), 2);
    assert_eq!(out[1].scans, 1);
}

/// A scan of one ray whose time is known only within `[earliest, latest]`,
/// stamped at the middle.
fn uncertain(sequence: u32, earliest: u64, latest: u64, range: f32) -> RangeScan {
    RangeScan {
        stamp_bound: StampBound::Within {
            earliest_ns: earliest,
            latest_ns: latest,
        },
        ..scan(
            sequence,
            lateness::best_estimate_ns(earliest, latest),
            vec![ray(0.0, range, 0)],
        )
    }
}

/// A unit 1 m up panning about z, the beam 50° down (as the device tests).
fn panning(motion: MountMotion) -> MovingMount {
    MovingMount {
        base: "0,0,1,0,0,0".parse().unwrap(),
        axis: DVec3::Z,
        sensor: "0,0,0,0,50,0".parse().unwrap(),
        motion,
    }
}

#[test]
fn a_reading_of_uncertain_time_carries_its_position_error_into_the_cloud() {
    let mount = panning(MountMotion::Profile("rotate:1".parse().unwrap()));
    let mut assembler = CloudAssembler::new(AssemblyConfig::fixed(mount)).unwrap();
    let mut out = Vec::new();
    // ±2 ms at 2π rad/s, 2 m along a beam 50° down: 2 m · cos 50° from the
    // axis, turned by up to 4π/1000 rad.
    assembler.push_scan(uncertain(0, T0, T0 + 4 * MS, 2.0), &mut out);
    let lever = 2.0 * 50f64.to_radians().cos();
    let expected = lateness::turn_displacement_m(lever, TAU * 0.002);
    assert_eq!(out.len(), 1);
    assert!(
        (out[0].position_error_m - expected).abs() < 1e-6,
        "{} vs {expected}",
        out[0].position_error_m
    );
    assert!(expected > 0.015 && expected < 0.017, "{expected}");
    // A reading taken as exact adds nothing.
    assembler.push_scan(scan(1, T0, vec![ray(0.0, 2.0, 0)]), &mut out);
    assert_eq!(out[1].position_error_m, 0.0);
    // 100 ms either way is over 0.25 m off: dropped, counted.
    assembler.push_scan(uncertain(2, T0, T0 + 200 * MS, 2.0), &mut out);
    assert_eq!(out.len(), 2);
    assert_eq!(assembler.stats().readings_late_beyond_bound, 1);
    // No bound at all: dropped, counted; an invalid reading is not counted.
    let mut lost = scan(3, T0, vec![ray(0.0, 2.0, 0), ray(0.0, f32::NAN, 0)]);
    lost.stamp_bound = StampBound::Unbounded;
    assembler.push_scan(lost, &mut out);
    assert_eq!(out.len(), 2);
    assert_eq!(assembler.stats().readings_late_unbounded, 1);
    assert_eq!(assembler.stats().invalid_rays, 1);
    // A fixed mount does not turn: lateness moves nothing.
    let fixed = MovingMount::fixed(MountPose::default());
    let mut still = CloudAssembler::new(AssemblyConfig::fixed(fixed)).unwrap();
    still.push_scan(uncertain(0, T0, T0 + 900 * MS, 2.0), &mut out);
    assert_eq!(out[2].position_error_m, 0.0);
    // The maximum must be a positive number.
    let bad = AssemblyConfig {
        max_position_error_m: f64::NAN,
        ..AssemblyConfig::fixed(MovingMount::fixed(MountPose::default()))
    };
    assert!(CloudAssembler::new(bad).is_err());
}

#[test]
fn a_joint_mount_bounds_the_turn_by_the_samples_over_the_readings_bound() {
    let mut assembler = CloudAssembler::new(AssemblyConfig::fixed(panning(MountMotion::Joint {
        name: "pan".into(),
    })))
    .unwrap();
    let mut out = Vec::new();
    // Still, then turning 0.1 rad in 10 ms, then still.
    assembler.push_joint(T0, 0.0, &mut out);
    assembler.push_joint(T0 + 10 * MS, 0.0, &mut out);
    assembler.push_scan(uncertain(0, T0 + 8 * MS, T0 + 16 * MS, 2.0), &mut out);
    assert!(out.is_empty(), "waits for samples up to the bound's end");
    assembler.push_joint(T0 + 20 * MS, 0.1, &mut out);
    assembler.push_joint(T0 + 30 * MS, 0.1, &mut out);
    assert_eq!(out.len(), 1);
    // Placed at 12 ms (0.02 rad); the joint was at 0 at 8 ms and 0.06 at
    // 16 ms: up to 0.04 rad off.
    let lever = 2.0 * 50f64.to_radians().cos();
    let expected = lateness::turn_displacement_m(lever, 0.04);
    assert!(
        (out[0].position_error_m - expected).abs() < 1e-6,
        "{} vs {expected}",
        out[0].position_error_m
    );
}

proptest::proptest! {
    /// Wherever inside its bound a reading was really measured, the point
    /// the assembler placed is within the cloud's stated position error of
    /// where it really is.
    #[test]
    fn every_point_lies_within_the_clouds_stated_error_of_the_truth(
        profile in proptest::sample::select(vec!["rotate:1", "sine:60:0.7", "triangle:30:2:10"]),
        offset_ms in 0u64..4_000,
        width_us in 0u64..20_000,
        truth_at in 0.0f64..=1.0,
        range in 0.2f32..10.0,
        sensor_yaw in -90.0f64..90.0,
    ) {
        let motion = MountMotion::Profile(profile.parse().unwrap());
        let mut mount = panning(motion);
        mount.sensor = MountPose::from_xyz_rpy([0.1, 0.05, 0.0], [0.0, 0.7, sensor_yaw.to_radians()]);
        let config = AssemblyConfig {
            max_position_error_m: f64::INFINITY,
            ..AssemblyConfig::fixed(mount.clone())
        };
        let mut assembler = CloudAssembler::new(config).unwrap();
        let earliest = T0 + offset_ms * MS;
        let latest = earliest + width_us * 1_000;
        let mut out = Vec::new();
        assembler.push_scan(uncertain(0, earliest, latest, range), &mut out);
        let truth_ns = earliest + ((latest - earliest) as f64 * truth_at) as u64;
        let (angle, _) = mount.angle_at(truth_ns, &JointTrack::new(0)).unwrap();
        let real = mount.pose_at_angle(angle).apply(DVec3::new(range as f64, 0.0, 0.0));
        let placed = DVec3::from_array(out[0].cloud.points[0].map(f64::from));
        let stated = out[0].position_error_m;
        proptest::prop_assert!(stated.is_finite() && stated >= 0.0);
        // f32 points: a few micrometres of rounding.
        proptest::prop_assert!((placed - real).length() <= stated + 1e-5,
            "{placed} is {} from {real}, stated {stated}", (placed - real).length());
    }
}
