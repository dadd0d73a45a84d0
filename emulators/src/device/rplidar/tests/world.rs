//! Test worlds for the RPLIDAR emulator.

use std::sync::{Arc, Mutex};

use crate::device::{RayReturn, RaySource};

/// A room whose wall lies `1.0 + 0.8 sin(3θ)` metres away along REP-103
/// angle θ (0.2 m to 1.8 m, so the parallax spans small and large dθ), with
/// reflectance 0.8.
pub struct Flower;

impl Flower {
    /// Range seen along clockwise device angle `deg`.
    pub fn range_cw(deg: f64) -> f64 {
        Self::range(-deg.to_radians())
    }

    fn range(angle: f64) -> f64 {
        1.0 + 0.8 * (3.0 * angle).sin()
    }
}

impl RaySource for Flower {
    fn cast(&self, angle: f64, _time: f64, max_range: f64) -> Option<RayReturn> {
        let range = Self::range(angle);
        (range <= max_range).then_some(RayReturn {
            range,
            reflectance: 0.8,
        })
    }
}

/// A wall at a fixed range that records every ray's angle.
pub struct Recorder {
    pub range: f64,
    pub angles: Arc<Mutex<Vec<f64>>>,
}

impl RaySource for Recorder {
    fn cast(&self, angle: f64, _time: f64, _max_range: f64) -> Option<RayReturn> {
        if let Ok(mut angles) = self.angles.lock() {
            angles.push(angle);
        }
        Some(RayReturn {
            range: self.range,
            reflectance: 0.5,
        })
    }
}

/// Nothing in range.
pub struct Void;

impl RaySource for Void {
    fn cast(&self, _angle: f64, _time: f64, _max_range: f64) -> Option<RayReturn> {
        None
    }
}
