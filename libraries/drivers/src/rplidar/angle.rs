//! RPLIDAR angles to REP-103.
//!
//! RPLIDAR reports headings in degrees [0, 360) measured **clockwise** (seen
//! from above) from the device's forward direction: protocol PDF Figure 4-6
//! "Angle and Distance Value Geometric Definition", and the A3M1 manual's
//! coordinate system ("the clockwise direction is the positive direction of
//! rotation"). REP-103 angles are counter-clockwise about +z, so a ray's
//! angle is the negated heading, wrapped to (−π, π]. (Drivers that publish
//! the raw heading mirror the scan: `Slamtec/rplidar_ros#31`,
//! `SteveMacenski/slam_toolbox#198`, research notes §5.)

use std::f32::consts::PI as PI_F32;
use std::f64::consts::PI;

/// One full turn in q16 degrees.
pub const TURN_Q16: i64 = 360 << 16;

/// The REP-103 angle, radians in (−π, π], of a clockwise heading in q16
/// degrees (any value; it is wrapped).
pub fn rep103(heading_q16: i64) -> f32 {
    let degrees = heading_q16.rem_euclid(TURN_Q16) as f64 / 65536.0;
    let mut radians = -degrees.to_radians();
    if radians <= -PI {
        radians += 2.0 * PI;
    }
    let angle = radians as f32;
    // Rounding to f32 can land exactly on −π (f32's π is above the real one).
    if angle <= -PI_F32 {
        PI_F32
    } else {
        angle
    }
}
