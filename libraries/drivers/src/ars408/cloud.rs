//! A complete cycle as a cloud: one point per target at (DistLong, DistLat,
//! 0) in the radar's frame, placed through the mount into the robot's, with
//! RCS as intensity and the radar's other values as named channels.
//!
//! Velocities, orientation and sizes stay as the radar reports them, in its
//! own frame (long = along the radar's x): the mount places positions only.

use super::config::RadarOutput;
use super::cycle::CompleteCycle;
use super::layout::general;
use crate::assembly::MountPose;
use crate::can_device::SensorCloud;
use crate::Scan;
use glam::DVec3;
use shroud_msg::PointChannel;

/// The channels of a cluster cloud: always the four general ones, plus the
/// quality ones when the radar sends quality frames.
pub const CLUSTER_CHANNELS: [&str; 8] = [
    "velocity_long",
    "velocity_lat",
    "dyn_prop",
    "rcs",
    "dist_long_rms",
    "dist_lat_rms",
    "pdh0",
    "invalid_state",
];

/// The channels of an object cloud: general (with the track id), quality,
/// extended.
pub const OBJECT_CHANNELS: [&str; 13] = [
    "object_id",
    "velocity_long",
    "velocity_lat",
    "dyn_prop",
    "rcs",
    "dist_long_rms",
    "dist_lat_rms",
    "prob_of_exist",
    "meas_state",
    "length",
    "width",
    "orientation_deg",
    "class",
];

/// The cloud of `cycle`: stamp and `received` of its status frame, sequence =
/// the radar's MeasCounter. Quality and extended values are the shipped
/// DBC's codes (factor 1 there), as f32.
pub(super) fn cycle_cloud(
    cycle: &CompleteCycle,
    output: RadarOutput,
    mount: &MountPose,
) -> SensorCloud {
    let points = cycle
        .generals
        .iter()
        .map(|g| {
            let p = mount.apply(DVec3::new(g[general::DIST_LONG], g[general::DIST_LAT], 0.0));
            [p.x as f32, p.y as f32, p.z as f32]
        })
        .collect();
    let mut scan = Scan::new(cycle.status.meas_counter, cycle.status.stamp_ns, points);
    scan.intensity = Some(column(&cycle.generals, general::RCS));
    let mut channels = Vec::new();
    if output == RadarOutput::Objects {
        channels.push(PointChannel::new("object_id", column(&cycle.generals, 0)));
    }
    channels.extend([
        PointChannel::new("velocity_long", column(&cycle.generals, general::VREL_LONG)),
        PointChannel::new("velocity_lat", column(&cycle.generals, general::VREL_LAT)),
        PointChannel::new("dyn_prop", column(&cycle.generals, general::DYN_PROP)),
        PointChannel::new("rcs", column(&cycle.generals, general::RCS)),
    ]);
    // Quality and extended values, in the order of their `NAMES` lists
    // (layout.rs) after the id.
    let quality_names: [&str; 4] = match output {
        RadarOutput::Clusters => ["dist_long_rms", "dist_lat_rms", "pdh0", "invalid_state"],
        RadarOutput::Objects => [
            "dist_long_rms",
            "dist_lat_rms",
            "prob_of_exist",
            "meas_state",
        ],
    };
    if cycle.with_quality {
        for (k, name) in quality_names.into_iter().enumerate() {
            channels.push(PointChannel::new(name, column(&cycle.qualities, k + 1)));
        }
    }
    if cycle.with_extended {
        for (k, name) in ["length", "width", "orientation_deg", "class"]
            .into_iter()
            .enumerate()
        {
            channels.push(PointChannel::new(name, column(&cycle.extendeds, k + 1)));
        }
    }
    scan.channels = channels;
    SensorCloud {
        scan,
        received: cycle.status.received,
    }
}

fn column<const N: usize>(rows: &[[f64; N]], k: usize) -> Vec<f32> {
    rows.iter()
        .map(|row| row.get(k).copied().unwrap_or(f64::NAN) as f32)
        .collect()
}
