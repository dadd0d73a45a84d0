//! The cluster list: golden frames, whole cycles, and every way a cycle is
//! lost.

use super::support::*;
use crate::ars408::{Ars408Config, CLUSTER_CHANNELS};
use crate::assembly::MountPose;
use crate::can::CanFrame;
use crate::can_device::{CanDeviceDriver, CanDriverOutput};
use crate::device::DeviceState;

/// sensors.md §2.2's vector, by hand: id 3, DistLong (0x4F<<5 | 0xB2>>3) =
/// 2550 -> 10.0 m, DistLat ((0xB2&3)<<8 | 0x04) = 516 -> 0.9 m, vrel 0/0,
/// DynProp 1, RCS 0x8A = 138 -> 5.0 dBm².
const GOLDEN: [u8; 8] = [0x03, 0x4F, 0xB2, 0x04, 0x80, 0x20, 0x01, 0x8A];

#[test]
fn the_test_encoder_packs_the_golden_frame() {
    let built = cluster_general(0, General::at(3, 10.0, 0.9));
    assert_eq!(built.payload(), &GOLDEN);
}

#[test]
fn golden_cluster_in_a_one_cluster_cycle() {
    let (mut d, out) = driver(Ars408Config::default());
    assert_eq!(out, vec![CanDriverOutput::State(DeviceState::Connecting)]);
    // Clusters of a cycle carry ids 0..n-1: the golden frame as cluster 0.
    let mut golden0 = GOLDEN;
    golden0[0] = 0;
    let general = CanFrame::new(0x701, false, &golden0).unwrap();
    let out = feed(
        &mut d,
        10,
        &[
            radar_state(0, State::clusters(false)),
            cluster_status(0, 1, 0, 42),
            general,
            // The next status vouches for the cycle (its counter follows).
            cluster_status(0, 0, 0, 43),
        ],
    );
    assert!(out.contains(&CanDriverOutput::State(DeviceState::Streaming)));
    let clouds = clouds(&out);
    assert_eq!(clouds.len(), 1);
    let c = &clouds[0];
    assert_eq!(c.scan.points.len(), 1);
    let p = c.scan.points[0];
    assert!(
        close(p[0], 10.0) && close(p[1], 0.9) && p[2] == 0.0,
        "{p:?}"
    );
    assert_eq!(c.scan.intensity.as_deref(), Some(&[5.0f32][..]));
    assert_eq!(channel(c, "rcs"), &[5.0]);
    assert_eq!(channel(c, "dyn_prop"), &[1.0]);
    assert_eq!(channel(c, "velocity_long"), &[0.0]);
    assert_eq!(channel(c, "velocity_lat"), &[0.0]);
    assert_eq!(
        c.scan.channels.len(),
        4,
        "no quality channels without quality"
    );
    assert_eq!(c.scan.sequence, 42);
    // Stamp and receipt are the status frame's (the second frame fed, at 11 ms).
    assert_eq!(c.scan.stamp_ns, at(general, 11).stamp_ns);
    assert_eq!(c.received, host(11));
    assert_eq!(d.stats().scans, 1);
    assert_eq!(d.stats().total_errors(), 0);
}

#[test]
fn golden_frame_as_the_fourth_cluster() {
    let (mut d, _) = driver(Ars408Config::default());
    let mut frames = vec![
        radar_state(0, State::clusters(false)),
        cluster_status(0, 3, 1, 7),
    ];
    frames.extend((0..3).map(|id| cluster_general(0, General::at(id, 1.0 + id as f64, 0.1))));
    frames.push(CanFrame::new(0x701, false, &GOLDEN).unwrap());
    frames.push(cluster_status(0, 0, 0, 8));
    let clouds = clouds(&feed(&mut d, 0, &frames));
    assert_eq!(clouds.len(), 1);
    let p = clouds[0].scan.points[3];
    assert!(close(p[0], 10.0) && close(p[1], 0.9), "{p:?}");
    // Near + far = 4.
    assert_eq!(clouds[0].scan.points.len(), 4);
}

fn three_with_quality() -> Vec<CanFrame> {
    let mut frames = vec![cluster_status(0, 2, 1, 100)];
    let targets = [(0, 5.0, 1.1), (1, 20.0, -3.1), (2, 60.2, 0.1)];
    for (id, long, lat) in targets {
        let mut g = General::at(id, long, lat);
        g.vlong = -2.5;
        g.vlat = 0.75;
        g.dyn_prop = 3;
        g.rcs = -10.5;
        frames.push(cluster_general(0, g));
    }
    for id in 0..3 {
        frames.push(cluster_quality(0, id, 10 + id, 20 + id, 1, id));
    }
    frames
}

#[test]
fn three_clusters_with_quality() {
    let (mut d, _) = driver(Ars408Config::default());
    let mut frames = vec![radar_state(0, State::clusters(true))];
    frames.extend(three_with_quality());
    frames.push(cluster_status(0, 0, 0, 101));
    let out = feed(&mut d, 0, &frames);
    let clouds = clouds(&out);
    assert_eq!(clouds.len(), 1);
    let c = &clouds[0];
    let xs: Vec<f32> = c.scan.points.iter().map(|p| p[0]).collect();
    let ys: Vec<f32> = c.scan.points.iter().map(|p| p[1]).collect();
    for (got, want) in xs.iter().zip([5.0, 20.0, 60.2]) {
        assert!(close(*got, want), "{xs:?}");
    }
    for (got, want) in ys.iter().zip([1.1, -3.1, 0.1]) {
        assert!(close(*got, want), "{ys:?}");
    }
    let names: Vec<&str> = c.scan.channels.iter().map(|ch| ch.name.as_str()).collect();
    assert_eq!(names, CLUSTER_CHANNELS);
    assert_eq!(channel(c, "velocity_long"), &[-2.5; 3]);
    assert_eq!(channel(c, "velocity_lat"), &[0.75; 3]);
    assert_eq!(channel(c, "dyn_prop"), &[3.0; 3]);
    assert_eq!(channel(c, "rcs"), &[-10.5; 3]);
    assert_eq!(channel(c, "dist_long_rms"), &[10.0, 11.0, 12.0]);
    assert_eq!(channel(c, "dist_lat_rms"), &[20.0, 21.0, 22.0]);
    assert_eq!(channel(c, "pdh0"), &[1.0; 3]);
    assert_eq!(channel(c, "invalid_state"), &[0.0, 1.0, 2.0]);
    assert_eq!(c.scan.sequence, 100);
}

#[test]
fn quality_is_inferred_from_the_frames_before_any_radar_state() {
    // With quality frames: the cycle waits for them and carries them.
    let (mut d, _) = driver(Ars408Config::default());
    let mut frames = three_with_quality();
    frames.push(cluster_status(0, 0, 0, 101));
    let out = feed(&mut d, 0, &frames);
    let c = clouds(&out);
    assert_eq!(c.len(), 1);
    assert_eq!(channel(&c[0], "pdh0").len(), 3);
    // Without: the cycle is complete when the next status arrives.
    let (mut d, _) = driver(Ars408Config::default());
    let first = feed(
        &mut d,
        0,
        &[
            cluster_status(0, 1, 0, 1),
            cluster_general(0, General::at(0, 3.0, 0.1)),
        ],
    );
    assert!(clouds(&first).is_empty(), "undecided until the next status");
    let next = feed(&mut d, 10, &[cluster_status(0, 0, 0, 2)]);
    let c = clouds(&next);
    assert_eq!(c.len(), 1, "the pending cycle (the empty one is held)");
    assert_eq!(c[0].scan.points.len(), 1);
    assert_eq!(c[0].scan.channels.len(), 4);
    let c = clouds(&feed(&mut d, 20, &[cluster_status(0, 0, 0, 3)]));
    assert_eq!(c.len(), 1);
    assert_eq!(c[0].scan.points.len(), 0);
    assert_eq!(d.stats().total_errors(), 0);
    // Or when a RadarState says quality is off.
    let (mut d, _) = driver(Ars408Config::default());
    feed(
        &mut d,
        0,
        &[
            cluster_status(0, 1, 0, 1),
            cluster_general(0, General::at(0, 3.0, 0.1)),
        ],
    );
    let settled = feed(&mut d, 5, &[radar_state(0, State::clusters(false))]);
    assert!(
        clouds(&settled).is_empty(),
        "complete, held for the next status"
    );
    let c = clouds(&feed(&mut d, 6, &[cluster_status(0, 0, 0, 2)]));
    assert_eq!(c.len(), 1);
    assert_eq!(c[0].scan.points.len(), 1);
}

#[test]
fn zero_clusters_is_an_empty_cloud() {
    let (mut d, _) = driver(Ars408Config::default());
    let c = clouds(&feed(
        &mut d,
        0,
        &[
            radar_state(0, State::clusters(true)),
            cluster_status(0, 0, 0, 9),
            cluster_status(0, 0, 0, 10),
        ],
    ));
    assert_eq!(c.len(), 1);
    assert!(c[0].scan.points.is_empty());
    assert_eq!(c[0].scan.channels.len(), CLUSTER_CHANNELS.len());
    assert!(c[0].scan.channels.iter().all(|ch| ch.values.is_empty()));
}

fn cycle(counter: u64, ids: &[u64], announced: u64) -> Vec<CanFrame> {
    let mut frames = vec![cluster_status(0, announced, 0, counter)];
    frames.extend(
        ids.iter()
            .map(|id| cluster_general(0, General::at(*id, 10.0, 0.1))),
    );
    frames
}

#[test]
fn a_lost_general_drops_the_cycle_whole_and_the_next_is_fine() {
    let (mut d, _) = driver(Ars408Config::default());
    feed(&mut d, 0, &[radar_state(0, State::clusters(false))]);
    let out = feed(&mut d, 1, &cycle(1, &[0, 2, 3], 4));
    assert!(clouds(&out).is_empty());
    assert_eq!(d.stats().errors("incomplete_cycle"), 1);
    assert_eq!(d.stats().errors("lost_frame"), 1);
    // The rest of the broken cycle is ignored, not counted again.
    assert_eq!(d.stats().notes("dropped_cycle_frame"), 1);
    let mut frames = cycle(2, &[0, 1, 2], 3);
    frames.push(cluster_status(0, 0, 0, 3));
    let c = clouds(&feed(&mut d, 10, &frames));
    assert_eq!(c.len(), 1);
    assert_eq!(c[0].scan.points.len(), 3);
    assert_eq!(c[0].scan.sequence, 2);
    assert_eq!(d.stats().errors("incomplete_cycle"), 1);
}

#[test]
fn a_repeated_id_drops_the_cycle() {
    let (mut d, _) = driver(Ars408Config::default());
    feed(&mut d, 0, &[radar_state(0, State::clusters(false))]);
    let out = feed(&mut d, 1, &cycle(1, &[0, 0, 1], 2));
    assert!(clouds(&out).is_empty());
    assert_eq!(d.stats().errors("incomplete_cycle"), 1);
    assert_eq!(d.stats().errors("lost_frame"), 1);
}

#[test]
fn the_next_status_arriving_early_drops_the_short_cycle() {
    let (mut d, _) = driver(Ars408Config::default());
    feed(&mut d, 0, &[radar_state(0, State::clusters(false))]);
    let mut frames = cycle(1, &[0, 1], 3);
    frames.extend(cycle(2, &[0], 1));
    frames.push(cluster_status(0, 0, 0, 3));
    let c = clouds(&feed(&mut d, 1, &frames));
    assert_eq!(c.len(), 1, "only the second cycle");
    assert_eq!(c[0].scan.sequence, 2);
    assert_eq!(d.stats().errors("incomplete_cycle"), 1);
    assert_eq!(d.stats().errors("lost_frame"), 1);
}

#[test]
fn too_many_frames_or_a_lost_status_is_counted_once() {
    let (mut d, _) = driver(Ars408Config::default());
    feed(&mut d, 0, &[radar_state(0, State::clusters(false))]);
    // Cycle 1 announces 1 and is complete; the extra general has no open
    // cycle. It may be the next cycle's (its status lost), and then cycle 1
    // may hold frames of it too: the held cycle is dropped, counted once.
    let mut frames = cycle(1, &[0, 0, 1], 1);
    frames.push(cluster_status(0, 0, 0, 2));
    let c = clouds(&feed(&mut d, 1, &frames));
    assert!(c.is_empty());
    assert_eq!(d.stats().errors("incomplete_cycle"), 1);
    assert_eq!(d.stats().errors("lost_frame"), 1);
}

#[test]
fn a_lost_status_is_caught_by_the_counter_and_the_held_cycle_dropped() {
    let (mut d, _) = driver(Ars408Config::default());
    feed(&mut d, 0, &[radar_state(0, State::clusters(false))]);
    // Cycle 1 announces one cluster and loses it; cycle 2's status is lost
    // and its first general completes cycle 1 by count. Cycle 3's status
    // (counter 3, not 2) shows a status went missing: nothing is published.
    let mut frames = vec![cluster_status(0, 1, 0, 1)];
    frames.push(cluster_general(0, General::at(0, 20.0, 0.1)));
    frames.push(cluster_status(0, 0, 0, 3));
    let c = clouds(&feed(&mut d, 1, &frames));
    assert!(c.is_empty(), "{c:?}");
    assert_eq!(d.stats().errors("lost_status"), 1);
    assert_eq!(d.stats().errors("incomplete_cycle"), 1);
    // The counter wraps: 65535 is followed by 0.
    let frames = [cluster_status(0, 0, 0, 65_535), cluster_status(0, 0, 0, 0)];
    let (mut d, _) = driver(Ars408Config::default());
    feed(&mut d, 0, &[radar_state(0, State::clusters(false))]);
    assert_eq!(clouds(&feed(&mut d, 1, &frames)).len(), 1);
    assert_eq!(d.stats().total_errors(), 0);
}

#[test]
fn frames_before_the_first_status_are_a_partial_cycle_not_an_error() {
    let (mut d, _) = driver(Ars408Config::default());
    let out = feed(&mut d, 0, &cycle(1, &[0, 1], 2)[1..]);
    assert!(clouds(&out).is_empty());
    assert_eq!(d.stats().notes("partial_first_cycle"), 2);
    assert_eq!(d.stats().total_errors(), 0);
}

#[test]
fn a_short_general_is_a_bad_frame_and_drops_the_cycle() {
    let (mut d, _) = driver(Ars408Config::default());
    feed(&mut d, 0, &[radar_state(0, State::clusters(false))]);
    let short = CanFrame::new(0x701, false, &[0, 1, 2]).unwrap();
    let frames = [
        cluster_status(0, 2, 0, 1),
        cluster_general(0, General::at(0, 1.0, 0.1)),
        short,
    ];
    assert!(clouds(&feed(&mut d, 1, &frames)).is_empty());
    assert_eq!(d.stats().errors("incomplete_cycle"), 1);
    assert_eq!(d.stats().errors("bad_frame"), 1);
    assert_eq!(d.stats().errors("lost_frame"), 0);
}

#[test]
fn sensor_id_2_moves_every_id_by_0x20() {
    let config = Ars408Config {
        sensor_id: 2,
        ..Ars408Config::default()
    };
    let (mut d, _) = driver(config);
    // Sensor 0's frames are another device's.
    let out = feed(
        &mut d,
        0,
        &[
            cluster_status(0, 1, 0, 1),
            cluster_general(0, General::at(0, 1.0, 0.1)),
        ],
    );
    assert!(clouds(&out).is_empty());
    assert_eq!(d.stats().notes("other_id"), 2);
    let mut state = State::clusters(false);
    state.sensor_id = 2;
    let frames = [
        radar_state(0x20, state),
        cluster_status(0x20, 1, 0, 5),
        cluster_general(0x20, General::at(0, 2.0, 0.1)),
        cluster_status(0x20, 0, 0, 6),
    ];
    assert_eq!(frames[1].id, 0x620);
    assert_eq!(frames[2].id, 0x721);
    let c = clouds(&feed(&mut d, 10, &frames));
    assert_eq!(c.len(), 1);
    assert!(close(c[0].scan.points[0][0], 2.0));
    assert_eq!(d.stats().errors("sensor_id_mismatch"), 0);
}

#[test]
fn a_yaw_of_90_degrees_turns_x_into_y() {
    let config = Ars408Config {
        mount: MountPose::from_xyz_rpy([1.0, 0.0, 0.5], [0.0, 0.0, std::f64::consts::FRAC_PI_2]),
        ..Ars408Config::default()
    };
    let (mut d, _) = driver(config);
    let frames = [
        radar_state(0, State::clusters(false)),
        cluster_status(0, 1, 0, 1),
        cluster_general(0, General::at(0, 10.0, 0.9)),
        cluster_status(0, 0, 0, 2),
    ];
    let c = clouds(&feed(&mut d, 0, &frames));
    // (10, 0.9, 0) turned 90° about z is (-0.9, 10, 0), then moved by (1, 0, 0.5).
    let p = c[0].scan.points[0];
    assert!(
        close(p[0], 0.1) && close(p[1], 10.0) && close(p[2], 0.5),
        "{p:?}"
    );
}

#[test]
fn foreign_remote_and_extended_frames_are_counted() {
    let (mut d, _) = driver(Ars408Config::default());
    let frames = [
        CanFrame::new(0x123, false, &[1, 2]).unwrap(),
        CanFrame::new(0x701, true, &GOLDEN).unwrap(),
        CanFrame::remote(0x600, false, 5).unwrap(),
        object_status(1, 1),
    ];
    let out = feed(&mut d, 0, &frames);
    assert!(clouds(&out).is_empty());
    assert_eq!(d.stats().notes("other_id"), 1);
    assert_eq!(d.stats().errors("bad_frame"), 2);
    assert_eq!(d.stats().notes("other_output"), 1);
}

#[test]
fn a_silent_radar_is_recovering_until_frames_return() {
    let (mut d, _) = driver(Ars408Config::default());
    feed(&mut d, 0, &[radar_state(0, State::clusters(false))]);
    let mut out = Vec::new();
    d.poll(host(900), &mut out);
    assert!(out.is_empty());
    d.poll(host(1000), &mut out);
    d.poll(host(1500), &mut out);
    assert_eq!(
        out,
        vec![CanDriverOutput::State(DeviceState::Recovering(
            "no frames from the radar for 1.0 s".into()
        ))]
    );
    assert_eq!(d.stats().errors("silent"), 1);
    let out = feed(&mut d, 1600, &[radar_state(0, State::clusters(false))]);
    assert!(out.contains(&CanDriverOutput::State(DeviceState::Streaming)));
}

#[test]
fn disconnect_cuts_the_open_cycle() {
    let (mut d, _) = driver(Ars408Config::default());
    feed(&mut d, 0, &[radar_state(0, State::clusters(false))]);
    feed(&mut d, 1, &cycle(1, &[0], 2));
    let mut out = Vec::new();
    d.disconnect(&mut out);
    assert_eq!(out, vec![CanDriverOutput::State(DeviceState::Disconnected)]);
    assert_eq!(d.stats().notes("cycle_cut"), 1);
    assert_eq!(d.stats().total_errors(), 0);
}

#[test]
fn health_names_the_set_error_bits_and_reports_changes_only() {
    let (mut d, _) = driver(Ars408Config::default());
    let ok = State::clusters(false);
    let mut bad = ok;
    bad.errors = [false, true, false, false, true];
    let health = |out: &[CanDriverOutput]| -> Vec<(bool, String)> {
        out.iter()
            .filter_map(|o| match o {
                CanDriverOutput::Health { ok, detail } => Some((*ok, detail.clone())),
                _ => None,
            })
            .collect()
    };
    let out = feed(
        &mut d,
        0,
        &[
            radar_state(0, ok),
            radar_state(0, ok),
            radar_state(0, bad),
            radar_state(0, bad),
        ],
    );
    assert_eq!(
        health(&out),
        vec![
            (true, "no errors".to_owned()),
            (false, "interference; voltage error".to_owned())
        ]
    );
    let identities = out
        .iter()
        .filter(|o| matches!(o, CanDriverOutput::Identity(_)))
        .count();
    assert_eq!(identities, 1, "the configuration did not change");
    let Some(CanDriverOutput::Identity(pairs)) = out
        .iter()
        .find(|o| matches!(o, CanDriverOutput::Identity(_)))
    else {
        unreachable!()
    };
    let get = |k: &str| {
        pairs
            .iter()
            .find(|(key, _)| key == k)
            .map(|(_, v)| v.as_str())
    };
    assert_eq!(get("output_type"), Some("clusters"));
    assert_eq!(get("max_distance_m"), Some("196"));
    assert_eq!(get("send_quality"), Some("false"));
}

#[test]
fn version_id_joins_the_identity() {
    let (mut d, _) = driver(Ars408Config::default());
    let mut data = [0; 8];
    put(&mut data, 7, 8, 4);
    put(&mut data, 15, 8, 21);
    put(&mut data, 23, 8, 3);
    put(&mut data, 25, 1, 1);
    let out = feed(&mut d, 0, &[frame(0x700, 4, data)]);
    let expected = vec![
        ("firmware".to_owned(), "4.21.3".to_owned()),
        ("extended_range".to_owned(), "true".to_owned()),
        ("country_code".to_owned(), "0".to_owned()),
    ];
    assert!(
        out.contains(&CanDriverOutput::Identity(expected)),
        "{out:?}"
    );
}
