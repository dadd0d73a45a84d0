//! A table-top scene: a flat table with boxes and a cylinder standing on it, seen
//! from above. Its steep jumps at object rims, skew to the grid for the cylinder,
//! show the aliasing of tensor-product surrogates.

use crate::error::{
    check_finite, check_non_negative, check_points, check_range, check_rectangle, SceneError,
};
use crate::sampling::{stream_rng, symmetric, uniform, SceneRng};
use crate::table_objects::{TableBox, TableCylinder};
use serde::{Deserialize, Serialize};

/// Stream tag separating this scene's random numbers from the other scenes'.
const STREAM_TAG: u64 = 0x5441_424C_4554_4F50; // "TABLETOP"

/// Scattered points on the top-most surface seen from above (table plane and object
/// tops, uniform over the table rectangle), followed by points on the side walls of
/// the boxes and cylinders (uniform by wall area). Height noise applies to all.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct TableTop {
    /// Total number of points (top surfaces plus walls).
    pub points: usize,
    /// Lower-left corner of the table rectangle (where top points are sampled).
    pub table_min: [f64; 2],
    /// Upper-right corner of the table rectangle.
    pub table_max: [f64; 2],
    /// Height of the table plane.
    pub table_height: f64,
    /// Axis-aligned boxes standing on the table.
    pub boxes: Vec<TableBox>,
    /// Upright cylinders standing on the table.
    pub cylinders: Vec<TableCylinder>,
    /// Fraction of the points placed on side walls, in [0, 1] (ignored, i.e. all
    /// points go on top surfaces, when there are no objects).
    pub wall_fraction: f64,
    /// Amplitude of uniform height noise in `[-noise, noise]`, >= 0.
    pub noise: f64,
    /// Seed of the random stream; fixes the cloud exactly.
    pub seed: u64,
}

impl Default for TableTop {
    /// An 8 x 6 table with three boxes of different heights and one cylinder,
    /// none touching, 15 % of the points on walls and a little noise.
    fn default() -> Self {
        Self {
            points: 30_000,
            table_min: [-4.0, -3.0],
            table_max: [4.0, 3.0],
            table_height: 0.0,
            boxes: vec![
                TableBox {
                    min: [-3.0, -2.0],
                    max: [-1.5, -0.5],
                    height: 1.0,
                },
                TableBox {
                    min: [0.5, 0.8],
                    max: [2.5, 2.2],
                    height: 0.6,
                },
                TableBox {
                    min: [1.0, -2.5],
                    max: [3.2, -1.5],
                    height: 1.4,
                },
            ],
            cylinders: vec![TableCylinder {
                centre: [-1.0, 1.5],
                radius: 0.8,
                height: 1.2,
            }],
            wall_fraction: 0.15,
            noise: 0.005,
            seed: 0,
        }
    }
}

/// One object's side walls, with the running total of wall area up to and
/// including it, for area-weighted selection.
struct Wall<'a> {
    cumulative_area: f64,
    solid: Solid<'a>,
}

enum Solid<'a> {
    Box(&'a TableBox),
    Cylinder(&'a TableCylinder),
}

impl TableTop {
    /// Height of the top-most surface at `(x, y)`: the tallest object whose
    /// footprint contains the point, else the table plane (which extends
    /// everywhere; only sampling is limited to the table rectangle).
    pub fn height(&self, x: f64, y: f64) -> f64 {
        let boxes = self
            .boxes
            .iter()
            .filter(|b| b.contains(x, y))
            .map(|b| b.height);
        let cylinders = self
            .cylinders
            .iter()
            .filter(|c| c.contains(x, y))
            .map(|c| c.height);
        self.table_height + boxes.chain(cylinders).fold(0.0, f64::max)
    }

    /// Number of points on the top surfaces and on the walls; they sum to `points`.
    pub fn counts(&self) -> [usize; 2] {
        if self.walls().is_empty() {
            return [self.points, 0];
        }
        let walls = ((self.points as f64 * self.wall_fraction).round() as usize).min(self.points);
        [self.points - walls, walls]
    }

    /// Checks every parameter; `generate` calls this first.
    pub fn validate(&self) -> Result<(), SceneError> {
        check_points("points", self.points)?;
        check_rectangle("table", self.table_min, self.table_max)?;
        check_finite("table_height", self.table_height)?;
        check_range("wall_fraction", self.wall_fraction, 0.0, 1.0)?;
        check_non_negative("noise", self.noise)?;
        self.boxes
            .iter()
            .enumerate()
            .try_for_each(|(i, b)| b.validate(&format!("boxes[{i}]")))?;
        self.cylinders
            .iter()
            .enumerate()
            .try_for_each(|(i, c)| c.validate(&format!("cylinders[{i}]")))
    }

    /// The scattered cloud: top-surface points first, then wall points. Top
    /// heights are evaluated at the f32-rounded `(x, y)` that is emitted, so a
    /// point next to a rim never lands on the wrong side of it.
    pub fn generate(&self) -> Result<Vec<[f32; 3]>, SceneError> {
        self.validate()?;
        let mut rng = stream_rng(self.seed, &[STREAM_TAG]);
        let [tops, wall_count] = self.counts();
        let mut cloud = Vec::with_capacity(self.points);
        cloud.extend((0..tops).map(|_| self.top_point(&mut rng)));
        let walls = self.walls();
        cloud.extend((0..wall_count).map(|_| self.wall_point(&walls, &mut rng)));
        Ok(cloud)
    }

    fn top_point(&self, rng: &mut SceneRng) -> [f32; 3] {
        let x = uniform(rng, self.table_min[0], self.table_max[0]) as f32;
        let y = uniform(rng, self.table_min[1], self.table_max[1]) as f32;
        let z = self.height(f64::from(x), f64::from(y)) + symmetric(rng, self.noise);
        [x, y, z as f32]
    }

    /// Picks a wall with probability proportional to its area, then a point on it.
    /// Only called when `walls` is non-empty.
    fn wall_point(&self, walls: &[Wall], rng: &mut SceneRng) -> [f32; 3] {
        let total = walls.last().map_or(0.0, |w| w.cumulative_area);
        let target = uniform(rng, 0.0, total);
        let index = walls.partition_point(|w| w.cumulative_area <= target);
        let [x, y, z] = match walls.get(index).or(walls.last()).map(|w| &w.solid) {
            Some(Solid::Box(b)) => b.wall_point(rng, self.table_height),
            Some(Solid::Cylinder(c)) => c.wall_point(rng, self.table_height),
            None => [0.0; 3],
        };
        [x as f32, y as f32, (z + symmetric(rng, self.noise)) as f32]
    }

    /// All side walls with their cumulative areas (objects are validated to have
    /// positive areas, so the totals increase strictly).
    fn walls(&self) -> Vec<Wall<'_>> {
        let boxes = self.boxes.iter().map(|b| (b.wall_area(), Solid::Box(b)));
        let cylinders = self
            .cylinders
            .iter()
            .map(|c| (c.wall_area(), Solid::Cylinder(c)));
        let mut total = 0.0;
        boxes
            .chain(cylinders)
            .map(|(area, solid)| {
                total += area;
                Wall {
                    cumulative_area: total,
                    solid,
                }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Whether `(x, y)` lies on the side wall of `scene`'s object, allowing for the
    /// f32 rounding of the emitted coordinates.
    fn wall_top_at(scene: &TableTop, x: f64, y: f64) -> Option<f64> {
        let eps = 1e-5;
        let boxes = scene.boxes.iter().filter(|b| {
            let grown = TableBox {
                min: [b.min[0] - eps, b.min[1] - eps],
                max: [b.max[0] + eps, b.max[1] + eps],
                ..**b
            };
            let shrunk = TableBox {
                min: [b.min[0] + eps, b.min[1] + eps],
                max: [b.max[0] - eps, b.max[1] - eps],
                ..**b
            };
            grown.contains(x, y) && !shrunk.contains(x, y)
        });
        let cylinders = scene
            .cylinders
            .iter()
            .filter(|c| ((x - c.centre[0]).hypot(y - c.centre[1]) - c.radius).abs() < eps);
        let heights = boxes.map(|b| b.height).chain(cylinders.map(|c| c.height));
        heights.reduce(f64::max)
    }

    #[test]
    fn same_seed_gives_same_points() {
        let scene = TableTop::default();
        assert_eq!(scene.generate().unwrap(), scene.generate().unwrap());
        let other = TableTop {
            seed: 2,
            ..TableTop::default()
        };
        assert_ne!(scene.generate().unwrap(), other.generate().unwrap());
    }

    #[test]
    fn point_count_is_exact() {
        for (points, wall_fraction) in [(1, 0.15), (2, 0.5), (30_000, 0.15), (10, 1.0), (10, 0.0)] {
            let scene = TableTop {
                points,
                wall_fraction,
                ..TableTop::default()
            };
            assert_eq!(scene.generate().unwrap().len(), points);
        }
        let bare = TableTop {
            boxes: vec![],
            cylinders: vec![],
            ..TableTop::default()
        };
        assert_eq!(bare.generate().unwrap().len(), bare.points);
    }

    #[test]
    fn top_points_lie_on_the_top_most_surface() {
        let scene = TableTop::default();
        let cloud = scene.generate().unwrap();
        let [tops, _] = scene.counts();
        for &[x, y, z] in &cloud[..tops] {
            let h = scene.height(f64::from(x), f64::from(y));
            assert!((f64::from(z) - h).abs() <= scene.noise + 1e-6, "{z} vs {h}");
        }
        let raised = cloud[..tops]
            .iter()
            .filter(|p| f64::from(p[2]) > scene.noise + 1e-6)
            .count();
        assert!(
            raised > 0 && raised < tops,
            "objects must be hit but not cover the table"
        );
    }

    #[test]
    fn wall_points_lie_on_object_walls() {
        let scene = TableTop::default();
        let cloud = scene.generate().unwrap();
        let [tops, walls] = scene.counts();
        assert_eq!(walls, 4_500);
        for &[x, y, z] in &cloud[tops..] {
            let top = wall_top_at(&scene, f64::from(x), f64::from(y));
            let top = top.unwrap_or_else(|| panic!("({x}, {y}) is on no wall"));
            let z = f64::from(z) - scene.table_height;
            assert!(
                z >= -scene.noise - 1e-6 && z <= top + scene.noise + 1e-6,
                "{z} above {top}"
            );
        }
    }

    #[test]
    fn height_is_the_tallest_footprint() {
        let scene = TableTop::default();
        assert_eq!(scene.height(-2.0, -1.0), 1.0);
        assert_eq!(scene.height(-1.0, 1.5), 1.2);
        assert_eq!(scene.height(0.0, 0.0), 0.0);
        assert_eq!(scene.height(100.0, 100.0), 0.0);
    }

    #[test]
    fn bad_parameters_are_errors_naming_them() {
        let base = TableTop::default();
        let mut bad_box = base.clone();
        bad_box.boxes[2].max = [0.0, 0.0];
        let mut bad_cylinder = base.clone();
        bad_cylinder.cylinders[0].radius = 0.0;
        let cases = [
            (
                TableTop {
                    points: 0,
                    ..base.clone()
                },
                "points",
            ),
            (
                TableTop {
                    table_max: [-5.0, 3.0],
                    ..base.clone()
                },
                "table",
            ),
            (
                TableTop {
                    table_height: f64::NAN,
                    ..base.clone()
                },
                "table_height",
            ),
            (
                TableTop {
                    wall_fraction: -0.1,
                    ..base.clone()
                },
                "wall_fraction",
            ),
            (
                TableTop {
                    noise: f64::INFINITY,
                    ..base.clone()
                },
                "noise",
            ),
            (bad_box, "boxes[2]"),
            (bad_cylinder, "cylinders[0].radius"),
        ];
        for (scene, name) in cases {
            let err = scene.generate().unwrap_err();
            assert!(err.to_string().contains(name), "{name}: {err}");
        }
    }

    #[test]
    fn config_round_trips_through_json() {
        let scene = TableTop {
            seed: 11,
            ..TableTop::default()
        };
        let json = serde_json::to_string(&scene).unwrap();
        assert_eq!(serde_json::from_str::<TableTop>(&json).unwrap(), scene);
    }
}
