//! The object list: quality and extended frames, track ids, and frames of
//! the cluster list while objects are selected.

use super::support::*;
use crate::ars408::{Ars408Config, RadarOutput, OBJECT_CHANNELS};
use crate::can_device::CanDeviceDriver;

fn objects() -> Ars408Config {
    Ars408Config {
        output: RadarOutput::Objects,
        ..Ars408Config::default()
    }
}

fn objects_state(quality: bool, ext: bool) -> State {
    State {
        max_distance_m: 196,
        output_type: 1,
        quality,
        ext_info: ext,
        ..State::default()
    }
}

#[test]
fn an_object_cycle_with_quality_and_extended_info() {
    let (mut d, _) = driver(objects());
    let mut a = General::at(7, 12.4, -1.2);
    a.vlong = 3.25;
    let b = General::at(12, 40.0, 6.0);
    let frames = [
        radar_state(0, objects_state(true, true)),
        object_status(2, 300),
        object_general(a),
        object_general(b),
        object_quality(7, 1, 5),
        object_quality(12, 2, 7),
        object_extended(7, 1, 90.0, 4.6, 1.8),
        object_extended(12, 2, -10.0, 1.0, 0.6),
        // The next status vouches for the cycle.
        object_status(0, 301),
    ];
    let c = clouds(&feed(&mut d, 0, &frames));
    assert_eq!(c.len(), 1);
    let c = &c[0];
    assert_eq!(c.scan.sequence, 300);
    assert_eq!(c.scan.points.len(), 2);
    let [p, q] = [c.scan.points[0], c.scan.points[1]];
    assert!(
        close(p[0], 12.4) && close(p[1], -1.2) && p[2] == 0.0,
        "{p:?}"
    );
    assert!(close(q[0], 40.0) && close(q[1], 6.0), "{q:?}");
    let names: Vec<&str> = c.scan.channels.iter().map(|ch| ch.name.as_str()).collect();
    assert_eq!(names, OBJECT_CHANNELS);
    assert_eq!(channel(c, "object_id"), &[7.0, 12.0]);
    assert_eq!(channel(c, "velocity_long"), &[3.25, 0.0]);
    assert_eq!(channel(c, "meas_state"), &[1.0, 2.0]);
    assert_eq!(channel(c, "prob_of_exist"), &[5.0, 7.0]);
    assert_eq!(channel(c, "class"), &[1.0, 2.0]);
    let orientation = channel(c, "orientation_deg");
    assert!(
        close(orientation[0], 90.0) && close(orientation[1], -10.0),
        "{orientation:?}"
    );
    let length = channel(c, "length");
    assert!(close(length[0], 4.6) && close(length[1], 1.0), "{length:?}");
    let width = channel(c, "width");
    assert!(close(width[0], 1.8) && close(width[1], 0.6), "{width:?}");
    assert_eq!(d.stats().total_errors(), 0);
}

#[test]
fn objects_without_quality_and_a_repeated_track_id() {
    let (mut d, _) = driver(objects());
    feed(&mut d, 0, &[radar_state(0, objects_state(false, true))]);
    let frames = [
        object_status(1, 1),
        object_general(General::at(3, 5.0, 0.0)),
        object_extended(3, 0, 0.0, 0.2, 0.2),
        object_status(0, 2),
    ];
    let c = clouds(&feed(&mut d, 1, &frames));
    assert_eq!(c.len(), 1);
    assert_eq!(c[0].scan.channels.len(), 9, "general + extended");
    // Two generals with one track id (the empty cycle 2 before it is whole).
    let frames = [
        object_status(2, 3),
        object_general(General::at(3, 5.0, 0.0)),
        object_general(General::at(3, 6.0, 0.0)),
    ];
    let c = clouds(&feed(&mut d, 10, &frames));
    assert_eq!(c.len(), 1);
    assert!(c[0].scan.points.is_empty());
    assert_eq!(d.stats().errors("incomplete_cycle"), 1);
    // An extended frame whose id is not the general's in that position.
    let frames = [
        object_status(1, 4),
        object_general(General::at(3, 5.0, 0.0)),
        object_extended(4, 0, 0.0, 0.2, 0.2),
    ];
    assert!(clouds(&feed(&mut d, 20, &frames)).is_empty());
    assert_eq!(d.stats().errors("incomplete_cycle"), 2);
}

#[test]
fn cluster_frames_are_another_output_when_objects_are_selected() {
    let (mut d, _) = driver(objects());
    let out = feed(
        &mut d,
        0,
        &[
            cluster_status(0, 1, 0, 1),
            cluster_general(0, General::at(0, 1.0, 0.1)),
        ],
    );
    assert!(clouds(&out).is_empty());
    assert_eq!(d.stats().notes("other_output"), 2);
    assert_eq!(d.stats().total_errors(), 0);
}
