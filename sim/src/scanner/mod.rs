//! A simulated range scanner: rays on a regular angular grid from a moving
//! sensor, cast against a triangle mesh through a [`Bvh`], with Gaussian range
//! noise and random dropouts. Deterministic for a given (seed, time), whatever the
//! number of threads: each row of rays draws from its own random stream.

mod bvh;
mod pose;
mod scenes;

pub use bvh::{Bvh, RayHit};
pub use pose::{ScanPose, SensorPose};
pub use scenes::{MeshScan, TableTopScan, TerrainScan};

use crate::error::{
    check_finite, check_non_negative, check_points, check_positive, SceneError, MAX_POINTS,
};
use crate::sampling::{stream_rng, time_key};
use rand::Rng;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use shroud_geometry::cloud::{dark_cones, EmptyRays};
use shroud_msg::{Aperture, FieldOfView, NoReturn};
use shroud_shapes::format::TriangleMesh;
use std::f64::consts::{PI, TAU};

/// Stream tag separating the scanner's random numbers from the scenes'.
const STREAM_TAG: u64 = 0x5343_414E_4E45_5221; // "SCANNER!"

/// How many rays one scan casts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ScanResolution {
    /// `columns` rays across the horizontal field of view times `rows` down the
    /// vertical one.
    Grid { columns: usize, rows: usize },
    /// About this many rays, on a grid whose angular spacing is the same in both
    /// directions (see [`RangeScanner::grid`]). Rays that miss the mesh, fall
    /// beyond the range or drop out return no point, so a scan has at most this
    /// many points.
    Points(usize),
}

/// A range scanner (think of a lidar or a depth camera with angular pixels):
/// `columns x rows` rays spread evenly in azimuth over `horizontal_fov` and in
/// elevation over `vertical_fov` around the viewing direction, each returning the
/// nearest surface point within `max_range`, its range perturbed by Gaussian noise.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct RangeScanner {
    /// Where the scanner is and what it looks at, over time.
    pub pose: ScanPose,
    /// Horizontal field of view in radians, in (0, π).
    pub horizontal_fov: f64,
    /// Vertical field of view in radians, in (0, π).
    pub vertical_fov: f64,
    /// Number of rays.
    pub resolution: ScanResolution,
    /// Surfaces farther than this (along the ray) are not seen; > 0.
    pub max_range: f64,
    /// Standard deviation of the Gaussian noise added to each range, >= 0.
    pub range_noise: f64,
    /// Probability that a ray returns nothing even though it hits, in [0, 1).
    pub dropout: f64,
    /// Seed of the noise and dropouts; with the time it fixes a scan exactly.
    pub seed: u64,
}

impl Default for RangeScanner {
    /// The default [`ScanPose`] (an orbit at radius 4, 9 above the origin), a
    /// 45° x 35° field of view, 30 000 rays, 50 units range, 5 mm range noise
    /// (for scenes in metres) and 1 % dropouts. Over the default table top or
    /// terrain (8 x 6 units around the origin) about 75 % of the rays hit.
    fn default() -> Self {
        Self {
            pose: ScanPose::default(),
            horizontal_fov: 45f64.to_radians(),
            vertical_fov: 35f64.to_radians(),
            resolution: ScanResolution::Points(30_000),
            max_range: 50.0,
            range_noise: 0.005,
            dropout: 0.01,
            seed: 0,
        }
    }
}

/// One scan: the points hit, their intensities and the sensor pose.
#[derive(Debug, Clone, PartialEq)]
pub struct ScanFrame {
    /// Hit points in world coordinates, row by row (top row first), left to right.
    pub points: Vec<[f32; 3]>,
    /// Per point, the cosine of the incidence angle (|ray · surface normal|) in
    /// [0, 1]: 1 where the ray meets the surface head-on.
    pub intensity: Vec<f32>,
    /// Where the scanner was and how it was oriented.
    pub sensor: SensorPose,
    /// Number of rays cast ([`RangeScanner::rays`]).
    pub rays: usize,
    /// The directions in which rays returned nothing (missed the mesh, fell
    /// beyond the range or dropped out), as a driver states them in the
    /// cloud ([`shroud_geometry::cloud::dark_cones`]); `None` when every group of
    /// empty rays is below the scan's resolution.
    pub no_return: Option<NoReturn>,
}

impl RangeScanner {
    /// Checks every parameter; `scan` calls this first.
    pub fn validate(&self) -> Result<(), SceneError> {
        self.pose.validate("pose")?;
        check_fov("horizontal_fov", self.horizontal_fov)?;
        check_fov("vertical_fov", self.vertical_fov)?;
        match self.resolution {
            ScanResolution::Grid { columns, rows } => {
                for (parameter, value) in
                    [("resolution.columns", columns), ("resolution.rows", rows)]
                {
                    if value == 0 {
                        return Err(SceneError::ZeroResolution {
                            parameter: parameter.into(),
                        });
                    }
                }
                let rays = columns.saturating_mul(rows);
                if rays > MAX_POINTS {
                    return Err(SceneError::TooManyPoints {
                        parameter: "resolution".into(),
                        value: rays,
                        max: MAX_POINTS,
                    });
                }
            }
            ScanResolution::Points(points) => {
                if points == 0 {
                    return Err(SceneError::ZeroResolution {
                        parameter: "resolution.points".into(),
                    });
                }
                check_points("resolution.points", points)?;
            }
        }
        let (rays, rows) = self.layout();
        if rows >= 2 && rays / rows >= 2 && self.ray_spread() >= MAX_RAY_SPREAD {
            // Its empty rays could not be stated as cones narrower than 90
            // degrees (`no_return`): such a grid says nothing of where it
            // looked anyway.
            return Err(SceneError::OutOfInterval {
                parameter: "resolution".into(),
                value: self.ray_spread(),
                interval: "[0, 1.55) rad between neighbouring rays",
            });
        }
        check_positive("max_range", self.max_range)?;
        check_non_negative("range_noise", self.range_noise)?;
        check_finite("dropout", self.dropout)?;
        if !(0.0..1.0).contains(&self.dropout) {
            return Err(SceneError::OutOfInterval {
                parameter: "dropout".into(),
                value: self.dropout,
                interval: "[0, 1)",
            });
        }
        Ok(())
    }

    /// The ray grid as `[columns, rows]`; for [`ScanResolution::Points`]`(n)`
    /// the columns of its widest row. With `Points(n)` there are `rows =
    /// round(sqrt(n * vertical_fov / horizontal_fov))` rows (at least 1, at most
    /// `n`) and exactly `n` rays, `n / rows` rounded down or up in each row (every
    /// row spread over the whole horizontal field of view), so the rays are about
    /// equally spaced in both angles.
    pub fn grid(&self) -> [usize; 2] {
        let (rays, rows) = self.layout();
        [rays.div_ceil(rows), rows]
    }

    /// Number of rays one scan casts: `columns * rows` for a grid, `n` for
    /// [`ScanResolution::Points`]`(n)`.
    pub fn rays(&self) -> usize {
        self.layout().0
    }

    /// Total rays and rows (both at least 1 for a valid scanner).
    fn layout(&self) -> (usize, usize) {
        match self.resolution {
            ScanResolution::Grid { columns, rows } => {
                (columns.saturating_mul(rows).max(1), rows.max(1))
            }
            ScanResolution::Points(n) => {
                let n = n.max(1);
                let aspect = self.vertical_fov / self.horizontal_fov;
                let rows = (n as f64 * aspect).sqrt().round();
                let rows = if rows.is_finite() {
                    rows.clamp(1.0, n as f64)
                } else {
                    1.0
                };
                (n, rows as usize)
            }
        }
    }

    /// Whether two scans at different times differ: the scanner moves, or the
    /// noise or dropouts (drawn afresh at each time) are on.
    pub fn is_animated(&self) -> bool {
        self.pose.moves() || self.range_noise > 0.0 || self.dropout > 0.0
    }

    /// A scanner that orbits `mesh`'s bounding box centre at 66° elevation (as
    /// the default pose), far enough for the box's bounding sphere to fit in the
    /// vertical field of view, with every other setting at its default. Fails on
    /// a mesh without finite vertices.
    pub fn orbiting(mesh: &TriangleMesh) -> Result<Self, SceneError> {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for v in &mesh.vertices {
            for k in 0..3 {
                lo[k] = lo[k].min(v[k]);
                hi[k] = hi[k].max(v[k]);
            }
        }
        let centre: [f64; 3] = std::array::from_fn(|k| 0.5 * (lo[k] + hi[k]));
        let radius = 0.5 * (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt();
        if !radius.is_finite() || centre.iter().any(|c| !c.is_finite()) {
            return Err(SceneError::EmptyMesh {
                reason: "it has no finite vertices to frame",
            });
        }
        let scanner = Self::default();
        let radius = radius.max(1e-3);
        let distance = radius / (0.5 * scanner.vertical_fov).sin();
        let (sin, cos) = (9f64).atan2(4.0).sin_cos();
        Ok(Self {
            pose: ScanPose::orbit(centre, distance * cos, distance * sin, 0.5),
            max_range: 2.0 * (distance + radius),
            ..scanner
        })
    }

    /// The region this scanner's rays span at `time` seconds, as a cloud
    /// states it: a rectangular pyramid from the optical centre along the
    /// viewing direction, cut at `max_range`. Its half angles are those of
    /// the outermost rays (half a ray spacing inside the nominal field of
    /// view; a sliver of 1e-9 rad when one ray spans the direction: a planar
    /// scan states a plane), so it holds no space between the rays and the
    /// nominal edge, which no ray crossed.
    /// The rays lie on an azimuth-elevation grid, which holds the pyramid:
    /// a direction within the pyramid's vertical half angle has an elevation
    /// at most that.
    pub fn field_of_view(&self, time: f64) -> Result<FieldOfView, SceneError> {
        self.validate()?;
        let sensor = self.pose.sensor(time)?;
        let (rays, rows) = self.layout();
        let outermost = |fov: f64, n: usize| {
            if n <= 1 {
                SLIVER
            } else {
                0.5 * fov * (1.0 - 1.0 / n as f64)
            }
        };
        // Rays start at the optical centre rounded to f32, as `scan` casts them.
        let apex = sensor.position.map(|c| f64::from(c as f32));
        Ok(FieldOfView {
            apex,
            axis: sensor.forward,
            aperture: Aperture::Rectangle {
                right: sensor.right,
                half_angles: [
                    outermost(self.horizontal_fov, rays / rows),
                    outermost(self.vertical_fov, rows),
                ],
            },
            max_range: self.max_range,
        })
    }

    /// Scans the mesh behind `bvh` at `time` seconds.
    pub fn scan(&self, bvh: &Bvh, time: f64) -> Result<ScanFrame, SceneError> {
        check_finite("time", time)?;
        self.validate()?;
        let sensor = self.pose.sensor(time)?;
        let (rays, rows) = self.layout();
        // Row r casts rays_before(r + 1) - rays_before(r) rays: every row the
        // same for a grid, within one of each other for a point budget.
        let rays_before = |row: usize| (row as u128 * rays as u128 / rows as u128) as usize;
        let angles = angle_at;
        let azimuth_table = |columns: usize| -> Vec<(f64, f64)> {
            (0..columns)
                .map(|c| angles(self.horizontal_fov, columns, c))
                .collect()
        };
        let narrow = rays / rows;
        let tables = [azimuth_table(narrow), azimuth_table(rays.div_ceil(rows))];
        let origin = sensor.position.map(|c| c as f32);
        let origin64 = origin.map(f64::from);
        let max_range = self.max_range as f32;
        let time_bits = time_key(time);
        let row_scans: Vec<RowScan> = (0..rows)
            .into_par_iter()
            .map(|row| {
                // Top row first: elevation decreasing.
                let elevation = angles(self.vertical_fov, rows, rows - 1 - row);
                let columns = rays_before(row + 1) - rays_before(row);
                let azimuths = &tables[usize::from(columns != narrow)];
                let mut rng = stream_rng(self.seed, &[STREAM_TAG, time_bits, row as u64]);
                let mut points = Vec::with_capacity(columns);
                let mut intensity = Vec::with_capacity(columns);
                let mut empty = Vec::with_capacity(columns);
                for &azimuth in azimuths {
                    let direction = sensor.direction(azimuth, elevation).map(|c| c as f32);
                    // Always draw the same three numbers per ray, so that neither
                    // the settings nor the hits shift the stream of later rays.
                    let keep = rng.random::<f64>() >= self.dropout;
                    let uniforms = (rng.random::<f64>(), rng.random::<f64>());
                    let hit = bvh.intersect(origin, direction, max_range).filter(|_| keep);
                    empty.push(hit.is_none());
                    let Some(hit) = hit else {
                        continue;
                    };
                    let noise = if self.range_noise > 0.0 {
                        self.range_noise * box_muller(uniforms)
                    } else {
                        0.0
                    };
                    let range = (f64::from(hit.distance) + noise).max(0.0);
                    let point: [f64; 3] =
                        std::array::from_fn(|k| origin64[k] + f64::from(direction[k]) * range);
                    points.push(point.map(|c| c as f32));
                    let cosine: f32 = (0..3).map(|k| direction[k] * hit.normal[k]).sum();
                    intensity.push(cosine.abs().min(1.0));
                }
                (points, intensity, empty)
            })
            .collect();
        let hits = row_scans.iter().map(|(p, _, _)| p.len()).sum();
        let no_return = self.no_return(&sensor, &row_scans, &tables, rows)?;
        let mut frame = ScanFrame {
            points: Vec::with_capacity(hits),
            intensity: Vec::with_capacity(hits),
            sensor,
            rays,
            no_return,
        };
        for (points, intensity, _) in row_scans {
            frame.points.extend(points);
            frame.intensity.extend(intensity);
        }
        Ok(frame)
    }

    /// A bound on the angle between a ray and any of its 8 neighbours: an
    /// azimuth step of the narrower rows (for a point budget plus as much
    /// again for the shift between rows of different widths), plus an
    /// elevation step (on the sphere an angle is at most the sum of the
    /// azimuth and elevation differences).
    fn ray_spread(&self) -> f64 {
        let (rays, rows) = self.layout();
        let narrow = (rays / rows).max(1);
        let shifts = match self.resolution {
            ScanResolution::Grid { .. } => 1.0,
            ScanResolution::Points(_) => 2.0,
        };
        shifts * self.horizontal_fov / narrow as f64 + self.vertical_fov / rows as f64
    }

    /// The empty rays of a scan as cones from the optical centre. Rows of a
    /// point budget differ by one ray at most; the grid is as wide as the
    /// widest row (the narrower rows' last cell is no ray); neighbours are
    /// at most [`Self::ray_spread`] apart.
    fn no_return(
        &self,
        sensor: &SensorPose,
        row_scans: &[RowScan],
        tables: &[Vec<(f64, f64)>; 2],
        rows: usize,
    ) -> Result<Option<NoReturn>, SceneError> {
        let columns = tables[1].len();
        let mut empty = vec![false; rows * columns];
        for (row, (_, _, flags)) in row_scans.iter().enumerate() {
            empty[row * columns..][..flags.len()].copy_from_slice(flags);
        }
        let direction = |k: usize| {
            let (row, column) = (k / columns, k % columns);
            let width = row_scans[row].2.len();
            let azimuth = tables[usize::from(width != tables[0].len())][column];
            let elevation = angle_at(self.vertical_fov, rows, rows - 1 - row);
            glam::DVec3::from_array(sensor.direction(azimuth, elevation))
        };
        let spread = self.ray_spread();
        let apex = sensor.position.map(|c| f64::from(c as f32));
        let rays = EmptyRays {
            rows,
            columns,
            empty: &empty,
        };
        dark_cones(apex, &rays, direction, spread).map_err(|e| SceneError::NoReturn {
            reason: e.to_string(),
        })
    }
}

/// Points, intensities and which rays were empty, of one row of a scan.
type RowScan = (Vec<[f32; 3]>, Vec<f32>, Vec<bool>);

/// Sine and cosine of ray `i`'s angle of `n` spread evenly over `fov`.
fn angle_at(fov: f64, n: usize, i: usize) -> (f64, f64) {
    (fov * ((i as f64 + 0.5) / n as f64 - 0.5)).sin_cos()
}

/// The widest angle between neighbouring rays (by [`RangeScanner::ray_spread`])
/// a grid of several rows and columns may have: a ray's cone must stay
/// narrower than 90 degrees (about 1.5708 rad). A scan with more than 1024
/// empty rays merges them into tiles, whose cones are wider still: a grid of
/// two or three rows (or columns) over a wide field of view can then fail
/// its scan with a named error (`SceneError::NoReturn`), never state less.
const MAX_RAY_SPREAD: f64 = 1.55;

/// The half angle a stated field of view takes across a single row or
/// column of rays (a field of view needs a positive one).
const SLIVER: f64 = 1e-9;

/// A field of view must lie strictly between 0 and π.
fn check_fov(parameter: &str, value: f64) -> Result<(), SceneError> {
    check_finite(parameter, value)?;
    if value > 0.0 && value < PI {
        Ok(())
    } else {
        Err(SceneError::OutOfInterval {
            parameter: parameter.into(),
            value,
            interval: "(0, π)",
        })
    }
}

/// A standard normal sample from two uniforms in [0, 1) by the Box–Muller
/// transform.
fn box_muller((first, second): (f64, f64)) -> f64 {
    let u1 = 1.0 - first; // in (0, 1]: the logarithm stays finite
    (-2.0 * u1.ln()).sqrt() * (TAU * second).cos()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::stream_rng;

    #[test]
    fn gaussian_has_unit_variance() {
        let mut rng = stream_rng(1, &[]);
        let n = 200_000;
        let samples: Vec<f64> = (0..n)
            .map(|_| box_muller((rng.random(), rng.random())))
            .collect();
        let mean = samples.iter().sum::<f64>() / n as f64;
        let var = samples.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n as f64;
        assert!(
            mean.abs() < 0.01 && (var - 1.0).abs() < 0.01,
            "{mean} {var}"
        );
        assert!(samples.iter().all(|x| x.is_finite()));
    }

    #[test]
    fn point_budgets_become_square_grids() {
        let mut scanner = RangeScanner {
            resolution: ScanResolution::Points(30_000),
            horizontal_fov: 1.2,
            vertical_fov: 0.9,
            ..RangeScanner::default()
        };
        assert_eq!((scanner.grid(), scanner.rays()), ([200, 150], 30_000));
        scanner.resolution = ScanResolution::Points(1);
        assert_eq!((scanner.grid(), scanner.rays()), ([1, 1], 1));
        scanner.resolution = ScanResolution::Points(300_007);
        assert_eq!((scanner.grid(), scanner.rays()), ([633, 474], 300_007));
        scanner.resolution = ScanResolution::Grid {
            columns: 7,
            rows: 3,
        };
        assert_eq!((scanner.grid(), scanner.rays()), ([7, 3], 21));
    }

    /// The stated field of view holds no direction outside the rays' angular
    /// span: every direction inside it (by the guard's own depth) has an
    /// azimuth and an elevation within those of the outermost rays. One ray
    /// across states a sliver.
    #[test]
    fn the_stated_field_of_view_lies_within_the_rays() {
        use shroud_guard::depth_inside;
        for (columns, rows) in [(1, 1), (2, 3), (7, 1), (40, 30)] {
            let scanner = RangeScanner {
                resolution: ScanResolution::Grid { columns, rows },
                horizontal_fov: 1.2,
                vertical_fov: 0.9,
                ..RangeScanner::default()
            };
            let fov = scanner.field_of_view(0.7).unwrap();
            fov.validate().unwrap();
            let sensor = scanner.pose.sensor(0.7).unwrap();
            // The outermost rays' angles, as `scan` spreads them.
            let span = |fov: f64, n: usize| fov * (0.5 - 0.5 / n as f64);
            let (az, el) = (span(1.2, columns), span(0.9, rows));
            let mut rng = stream_rng(3, &[]);
            let mut inside = 0;
            for _ in 0..20_000 {
                let (a, e) = (rng.random_range(-0.8..0.8), rng.random_range(-0.6..0.6));
                let d = sensor.direction(f64::sin_cos(a), f64::sin_cos(e));
                let p: [f64; 3] = std::array::from_fn(|k| fov.apex[k] + 3.0 * d[k]);
                if depth_inside(&fov, glam::DVec3::from_array(p)) > 0.0 {
                    inside += 1;
                    assert!(a.abs() <= az + 1e-9 && e.abs() <= el + 1e-9, "{a} {e}");
                }
            }
            // Not vacuous where the rays span an area.
            assert_eq!(inside > 0, columns > 1 && rows > 1, "{columns}x{rows}");
        }
    }
}
