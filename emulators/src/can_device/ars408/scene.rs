//! What the radar sees of the scene: the moving spheres, placed in the
//! radar's frame (x forward, y left, z up; the radar at the origin), turned
//! into clusters spread over their near sides and into one object each, plus
//! a few fixed clusters of a wall and the ground.
//!
//! Geometry only, no noise; the emulator adds the measurement noise.

use glam::DVec3;
use shroud_drivers::assembly::MountPose;
use shroud_sim::MovingSpheres;

/// Half the azimuth field of view: the ARS408-21's near scan covers ±60°.
pub const HALF_AZIMUTH_DEG: f64 = 60.0;
/// Half the elevation field of view the emulator gives the radar (the
/// datasheet's elevation beam is narrower; spheres slightly above or below
/// the radar's plane still show).
pub const HALF_ELEVATION_DEG: f64 = 20.0;
/// Clusters up to this range are counted as near-scan ones (0x600
/// NofClustersNear), the rest as far-scan ones: the near scan reaches 70 m.
pub const NEAR_RANGE_M: f64 = 70.0;
/// Fixed clusters in the radar's own frame, `[DistLong m, DistLat m, RCS
/// dBm²]`: a wall 40 m ahead and one ground return; stationary.
pub const STATIC_CLUSTERS: [[f64; 3]; 5] = [
    [40.0, -8.1, 12.0],
    [40.0, -2.9, 14.0],
    [40.0, 3.1, 14.0],
    [40.0, 8.3, 12.0],
    [6.0, 1.5, -12.0],
];
/// Half the arc of a sphere's near side that returns clusters.
const HALF_ARC_DEG: f64 = 50.0;
/// At most this many clusters per sphere.
const MAX_CLUSTERS_PER_SPHERE: usize = 8;
/// Central-difference step of the velocities and accelerations.
const DIFFERENCE_STEP_S: f64 = 1e-3;
/// Slower than this is stationary (DynProp 1).
pub const MOVING_SPEED_MPS: f64 = 0.05;

/// One reflection point, radar frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Detection {
    pub long: f64,
    pub lat: f64,
    pub vlong: f64,
    pub vlat: f64,
    pub rcs: f64,
    pub moving: bool,
}

impl Detection {
    pub(crate) fn range(&self) -> f64 {
        self.long.hypot(self.lat)
    }
}

/// A sphere the radar sees, radar frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Target {
    /// Which sphere (the object's id).
    pub index: usize,
    pub centre: DVec3,
    pub velocity: DVec3,
    pub acceleration: DVec3,
    pub radius: f64,
}

impl Target {
    pub(crate) fn moving(&self) -> bool {
        self.velocity.truncate().length() >= MOVING_SPEED_MPS
    }

    /// The radar cross-section a sphere of this size shows: its
    /// cross-sectional area π r² in dBm² (a perfectly conducting sphere's RCS
    /// is exactly that).
    pub(crate) fn rcs(&self) -> f64 {
        10.0 * (std::f64::consts::PI * self.radius * self.radius)
            .max(1e-6)
            .log10()
    }
}

/// Whether a point of the radar frame lies in the field of view within
/// `max_distance` metres.
fn in_view(point: DVec3, max_distance: f64) -> bool {
    let planar = point.x.hypot(point.y);
    let azimuth = point.y.atan2(point.x).to_degrees();
    let elevation = point.z.atan2(planar).to_degrees();
    point.x > 0.0
        && planar <= max_distance
        && azimuth.abs() <= HALF_AZIMUTH_DEG
        && elevation.abs() <= HALF_ELEVATION_DEG
}

/// The spheres whose centres the radar, mounted at `mount`, sees at `time`.
pub(crate) fn targets(
    spheres: &MovingSpheres,
    mount: &MountPose,
    time: f64,
    max_distance: f64,
) -> Vec<Target> {
    let to_radar = mount.rotation.inverse();
    let local = |p: [f64; 3]| to_radar * (DVec3::from_array(p) - mount.translation);
    let before = spheres.centres(time - DIFFERENCE_STEP_S);
    let now = spheres.centres(time);
    let after = spheres.centres(time + DIFFERENCE_STEP_S);
    let h = DIFFERENCE_STEP_S;
    (0..now.len())
        .filter_map(|index| {
            let (b, c, a) = (before.get(index)?, now.get(index)?, after.get(index)?);
            let (b, c, a) = (
                DVec3::from_array(*b),
                DVec3::from_array(*c),
                DVec3::from_array(*a),
            );
            let radius = f64::from(*spheres.radii.get(index)?);
            let target = Target {
                index,
                centre: local(c.to_array()),
                velocity: to_radar * ((a - b) / (2.0 * h)),
                acceleration: to_radar * ((a - 2.0 * c + b) / (h * h)),
                radius: if radius.is_finite() {
                    radius.max(0.0)
                } else {
                    0.0
                },
            };
            let usable = target.centre.is_finite() && target.velocity.is_finite();
            (usable && in_view(target.centre, max_distance)).then_some(target)
        })
        .collect()
}

/// The clusters of `targets` (spread over each sphere's near side, as seen
/// in the radar's x-y plane) and the static ones, within `max_distance`.
pub(crate) fn clusters(targets: &[Target], max_distance: f64) -> Vec<Detection> {
    let mut out = Vec::new();
    for target in targets {
        let centre = target.centre.truncate();
        let r = target.radius;
        if centre.length() <= r {
            continue; // the radar is inside the sphere's outline
        }
        let count = (3 + (2.0 * r).floor() as usize).min(MAX_CLUSTERS_PER_SPHERE);
        let facing = (-centre.y).atan2(-centre.x);
        let half_arc = HALF_ARC_DEG.to_radians();
        for j in 0..count {
            let fraction = j as f64 / (count - 1) as f64;
            let angle = facing + half_arc * (2.0 * fraction - 1.0);
            let point = centre + r * glam::DVec2::new(angle.cos(), angle.sin());
            let point3 = point.extend(target.centre.z);
            if !in_view(point3, max_distance) {
                continue;
            }
            out.push(Detection {
                long: point.x,
                lat: point.y,
                vlong: target.velocity.x,
                vlat: target.velocity.y,
                rcs: target.rcs(),
                moving: target.moving(),
            });
        }
    }
    for [long, lat, rcs] in STATIC_CLUSTERS {
        if in_view(DVec3::new(long, lat, 0.0), max_distance) {
            out.push(Detection {
                long,
                lat,
                vlong: 0.0,
                vlat: 0.0,
                rcs,
                moving: false,
            });
        }
    }
    out
}
