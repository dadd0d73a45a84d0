//! The solids standing on the table top: axis-aligned boxes and upright cylinders,
//! with their footprints (for heights) and side walls (for wall samples).

use crate::error::{check_finite_all, check_positive, check_rectangle, SceneError};
use crate::sampling::{uniform, SceneRng};
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

/// An axis-aligned box standing on the table: footprint `[min, max]`, top at
/// `height` above the table plane. Its edges run along the grid axes, so its jumps
/// are the easy case for a tensor-product spline.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TableBox {
    /// Lower-left corner of the footprint.
    pub min: [f64; 2],
    /// Upper-right corner of the footprint.
    pub max: [f64; 2],
    /// Height of the top face above the table, > 0.
    pub height: f64,
}

/// An upright cylinder standing on the table. Its rim crosses the grid in every
/// direction, so it shows the aliasing of steep jumps skew to the grid.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TableCylinder {
    /// Centre of the circular footprint.
    pub centre: [f64; 2],
    /// Radius of the footprint, > 0.
    pub radius: f64,
    /// Height of the top disc above the table, > 0.
    pub height: f64,
}

impl TableBox {
    /// Whether `(x, y)` lies in the footprint (boundary included).
    pub fn contains(&self, x: f64, y: f64) -> bool {
        (self.min[0]..=self.max[0]).contains(&x) && (self.min[1]..=self.max[1]).contains(&y)
    }

    /// Area of the four side walls.
    pub(crate) fn wall_area(&self) -> f64 {
        2.0 * (self.max[0] - self.min[0] + self.max[1] - self.min[1]) * self.height
    }

    /// A uniform point on the side walls: walk a uniform arc length around the
    /// footprint's perimeter, then pick a uniform height up the wall.
    pub(crate) fn wall_point(&self, rng: &mut SceneRng, base: f64) -> [f64; 3] {
        let (w, d) = (self.max[0] - self.min[0], self.max[1] - self.min[1]);
        let s = uniform(rng, 0.0, 2.0 * (w + d));
        let [x, y] = if s < w {
            [self.min[0] + s, self.min[1]]
        } else if s < w + d {
            [self.max[0], self.min[1] + (s - w)]
        } else if s < 2.0 * w + d {
            [self.max[0] - (s - w - d), self.max[1]]
        } else {
            [self.min[0], self.max[1] - (s - 2.0 * w - d)]
        };
        [x, y, base + uniform(rng, 0.0, self.height)]
    }

    /// A box needs a non-empty footprint and a positive height (else it has no walls).
    pub(crate) fn validate(&self, parameter: &str) -> Result<(), SceneError> {
        check_rectangle(parameter, self.min, self.max)?;
        check_positive(&format!("{parameter}.height"), self.height)
    }
}

impl TableCylinder {
    /// Whether `(x, y)` lies in the footprint disc (rim included).
    pub fn contains(&self, x: f64, y: f64) -> bool {
        (x - self.centre[0]).powi(2) + (y - self.centre[1]).powi(2) <= self.radius * self.radius
    }

    /// Area of the curved side wall.
    pub(crate) fn wall_area(&self) -> f64 {
        TAU * self.radius * self.height
    }

    /// A uniform point on the curved side wall.
    pub(crate) fn wall_point(&self, rng: &mut SceneRng, base: f64) -> [f64; 3] {
        let (sin, cos) = uniform(rng, 0.0, TAU).sin_cos();
        let z = base + uniform(rng, 0.0, self.height);
        [
            self.centre[0] + self.radius * cos,
            self.centre[1] + self.radius * sin,
            z,
        ]
    }

    /// A cylinder needs a finite centre and positive radius and height.
    pub(crate) fn validate(&self, parameter: &str) -> Result<(), SceneError> {
        check_finite_all(&format!("{parameter}.centre"), &self.centre)?;
        check_positive(&format!("{parameter}.radius"), self.radius)?;
        check_positive(&format!("{parameter}.height"), self.height)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::stream_rng;

    const BOX: TableBox = TableBox {
        min: [0.0, 0.0],
        max: [2.0, 1.0],
        height: 0.5,
    };
    const CYLINDER: TableCylinder = TableCylinder {
        centre: [1.0, 1.0],
        radius: 0.5,
        height: 2.0,
    };

    #[test]
    fn footprints_include_their_boundary() {
        assert!(BOX.contains(0.0, 1.0) && BOX.contains(1.0, 0.5) && !BOX.contains(2.1, 0.5));
        assert!(CYLINDER.contains(1.5, 1.0) && !CYLINDER.contains(1.4, 1.4));
    }

    #[test]
    fn wall_areas_match_geometry() {
        assert!((BOX.wall_area() - 3.0).abs() < 1e-12);
        assert!((CYLINDER.wall_area() - TAU * 0.5 * 2.0).abs() < 1e-12);
    }

    #[test]
    fn wall_points_lie_on_the_walls() {
        let mut rng = stream_rng(1, &[]);
        for _ in 0..1000 {
            let [x, y, z] = BOX.wall_point(&mut rng, 1.0);
            let on_edge = [x, y, 2.0 - x, 1.0 - y].iter().any(|g| g.abs() < 1e-12);
            assert!(BOX.contains(x, y) && on_edge && (1.0..=1.5).contains(&z));
            let [x, y, z] = CYLINDER.wall_point(&mut rng, 1.0);
            assert!(((x - 1.0).hypot(y - 1.0) - 0.5).abs() < 1e-12 && (1.0..=3.0).contains(&z));
        }
    }

    #[test]
    fn degenerate_solids_are_rejected() {
        let flat = TableBox { height: 0.0, ..BOX };
        assert!(flat
            .validate("boxes[0]")
            .unwrap_err()
            .to_string()
            .contains("boxes[0].height"));
        let thin = TableCylinder {
            radius: -1.0,
            ..CYLINDER
        };
        assert!(thin
            .validate("cylinders[0]")
            .unwrap_err()
            .to_string()
            .contains("cylinders[0].radius"));
    }
}
