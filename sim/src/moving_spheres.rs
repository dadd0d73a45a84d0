//! The paper's benchmark scene (Section 7, Figure 10): two spherical scatter clouds
//! moving relative to each other, so the top view shows steep jumps between them.

use crate::error::{check_finite, check_points, check_positive, check_range, SceneError};
use crate::path::LissajousPath;
use crate::sampling::{in_ball, on_sphere, stream_rng, time_key};
use serde::{Deserialize, Serialize};
use std::f64::consts::{FRAC_PI_2, PI};

/// Stream tag separating this scene's random numbers from the other scenes'.
const STREAM_TAG: u64 = 0x5350_4845_5245_5321; // "SPHERES!"

/// Two spheres whose centres follow [`LissajousPath`]s. The output lists the first
/// sphere's points first, then the second's.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct MovingSpheres {
    /// Total number of points over both spheres.
    pub points: usize,
    /// Radius of each sphere.
    pub radii: [f32; 2],
    /// Path of each sphere's centre over time.
    pub paths: [LissajousPath; 2],
    /// Seed of the random stream; with the time it fixes the cloud exactly.
    pub seed: u64,
    /// `false`: points uniform in the solid balls (the paper's "spherical scatter
    /// clouds"); `true`: points on the sphere surfaces only.
    pub surface_only: bool,
    /// Fraction of the points that belong to the first sphere, in [0, 1].
    pub split: f32,
    /// A floor under the spheres, as a real cell has (absent by default): a
    /// sensor looking down sees it wherever the spheres do not hide it, so a
    /// guard can tell the empty space above it from space nobody saw. Its
    /// points come after the spheres' and are not counted in `points`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub floor: Option<Floor>,
}

/// A square floor sampled on a regular grid, so that every cell of a fit over
/// it holds points (random sampling leaves holes, which are unseen space).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Floor {
    /// Height of the floor.
    pub z: f32,
    /// The floor spans `[-half_extent, half_extent]^2` around the origin.
    pub half_extent: f32,
    /// Distance between neighbouring floor points.
    pub spacing: f32,
}

/// Floor points at most, so that a typo in `spacing` cannot ask for billions.
pub const MAX_FLOOR_POINTS: usize = 1 << 20;

impl Floor {
    /// Points along each side of the grid.
    pub(crate) fn per_side(&self) -> usize {
        (2.0 * f64::from(self.half_extent) / f64::from(self.spacing)).floor() as usize + 1
    }

    pub(crate) fn validate(&self) -> Result<(), SceneError> {
        check_finite("floor.z", f64::from(self.z))?;
        check_positive("floor.half_extent", f64::from(self.half_extent))?;
        check_positive("floor.spacing", f64::from(self.spacing))?;
        let n = self.per_side();
        if n.saturating_mul(n) > MAX_FLOOR_POINTS {
            return Err(SceneError::TooManyPoints {
                parameter: "floor.spacing".into(),
                value: n.saturating_mul(n),
                max: MAX_FLOOR_POINTS,
            });
        }
        Ok(())
    }

    /// The grid's points, row after row.
    pub(crate) fn points(&self) -> impl Iterator<Item = [f32; 3]> + '_ {
        let n = self.per_side();
        let at = move |i: usize| -self.half_extent + i as f32 * self.spacing;
        (0..n).flat_map(move |j| (0..n).map(move |i| [at(i), at(j), self.z]))
    }
}

impl Default for MovingSpheres {
    /// A unit sphere wobbling near the origin and a smaller sphere orbiting it on an
    /// ellipse, higher up. Seen from above (down -z) the two silhouettes overlap
    /// during part of every 4π s loop and separate during the rest, and the line
    /// through the centres turns, so it is mostly skew to any grid.
    fn default() -> Self {
        let wobble = LissajousPath {
            centre: [0.0, 0.0, 0.0],
            amplitude: [0.3, 0.3, 0.1],
            angular_speed: [0.5, 0.5, 1.0],
            phase: [FRAC_PI_2, 0.0, 0.0],
        };
        let orbit = LissajousPath {
            centre: [0.0, 0.0, 0.8],
            amplitude: [2.2, 1.0, 0.2],
            angular_speed: [0.5, 0.5, 1.0],
            phase: [FRAC_PI_2, 0.0, PI],
        };
        Self {
            points: 30_000,
            radii: [1.0, 0.7],
            paths: [wobble, orbit],
            seed: 0,
            surface_only: false,
            split: 0.5,
            floor: None,
        }
    }
}

impl MovingSpheres {
    /// Sphere centres at `time` seconds (ground truth for tests and overlays).
    pub fn centres(&self, time: f64) -> [[f64; 3]; 2] {
        [self.paths[0].position(time), self.paths[1].position(time)]
    }

    /// Number of points drawn for each sphere; they sum to `points`.
    pub fn counts(&self) -> [usize; 2] {
        let first = (self.points as f64 * f64::from(self.split)).round() as usize;
        let first = first.min(self.points);
        [first, self.points - first]
    }

    /// Checks every parameter; `generate` calls this first.
    pub fn validate(&self) -> Result<(), SceneError> {
        check_points("points", self.points)?;
        check_positive("radii[0]", f64::from(self.radii[0]))?;
        check_positive("radii[1]", f64::from(self.radii[1]))?;
        check_range("split", f64::from(self.split), 0.0, 1.0)?;
        self.paths[0].validate("paths[0]")?;
        self.paths[1].validate("paths[1]")?;
        self.floor.as_ref().map_or(Ok(()), Floor::validate)
    }

    /// The cloud at `time` seconds. Deterministic in (config, time): each sphere
    /// draws from its own stream keyed by seed, time bits and sphere index.
    pub fn generate(&self, time: f64) -> Result<Vec<[f32; 3]>, SceneError> {
        self.validate()?;
        check_finite("time", time)?;
        let centres = self.centres(time);
        let sample = if self.surface_only {
            on_sphere
        } else {
            in_ball
        };
        let mut cloud = Vec::with_capacity(self.points);
        for (index, count) in self.counts().into_iter().enumerate() {
            let mut rng = stream_rng(self.seed, &[STREAM_TAG, time_key(time), index as u64]);
            let radius = f64::from(self.radii[index]);
            cloud.extend((0..count).map(|_| sample(&mut rng, centres[index], radius)));
        }
        if let Some(floor) = &self.floor {
            cloud.extend(floor.points());
        }
        Ok(cloud)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn distance(p: [f32; 3], c: [f64; 3]) -> f64 {
        p.iter()
            .zip(c)
            .map(|(&a, b)| (f64::from(a) - b).powi(2))
            .sum::<f64>()
            .sqrt()
    }

    #[test]
    fn same_seed_and_time_give_same_points() {
        let scene = MovingSpheres::default();
        assert_eq!(scene.generate(1.25).unwrap(), scene.generate(1.25).unwrap());
    }

    #[test]
    fn different_seeds_give_different_points() {
        let other = MovingSpheres {
            seed: 1,
            ..MovingSpheres::default()
        };
        assert_ne!(
            MovingSpheres::default().generate(0.0).unwrap(),
            other.generate(0.0).unwrap()
        );
    }

    #[test]
    fn different_times_give_different_clouds() {
        let scene = MovingSpheres::default();
        assert_ne!(scene.centres(0.0), scene.centres(1.0));
        assert_ne!(scene.generate(0.0).unwrap(), scene.generate(1.0).unwrap());
    }

    #[test]
    fn point_count_is_exact() {
        for (points, split) in [(1, 0.5), (30_001, 0.5), (10, 0.0), (10, 1.0), (7, 0.33)] {
            let scene = MovingSpheres {
                points,
                split,
                ..MovingSpheres::default()
            };
            assert_eq!(scene.generate(0.5).unwrap().len(), points);
            assert_eq!(scene.counts().iter().sum::<usize>(), points);
        }
    }

    #[test]
    fn a_floor_adds_a_regular_grid_under_the_spheres() {
        let floor = Floor {
            z: -0.5,
            half_extent: 1.0,
            spacing: 0.5,
        };
        let scene = MovingSpheres {
            points: 100,
            floor: Some(floor),
            ..MovingSpheres::default()
        };
        let cloud = scene.generate(0.0).unwrap();
        assert_eq!(cloud.len(), 100 + 25);
        assert!(cloud[100..].iter().all(|p| p[2] == -0.5));
        assert_eq!(cloud[100], [-1.0, -1.0, -0.5]);
        assert_eq!(cloud[124], [1.0, 1.0, -0.5]);
        for bad in [
            Floor {
                spacing: 0.0,
                ..floor
            },
            Floor {
                spacing: 1e-6,
                ..floor
            },
            Floor {
                z: f32::NAN,
                ..floor
            },
        ] {
            let scene = MovingSpheres {
                floor: Some(bad),
                ..MovingSpheres::default()
            };
            assert!(scene.generate(0.0).is_err(), "{bad:?}");
        }
    }

    #[test]
    fn volume_points_lie_inside_their_sphere() {
        let scene = MovingSpheres::default();
        let time = 2.0;
        let cloud = scene.generate(time).unwrap();
        let [first, _] = scene.counts();
        let centres = scene.centres(time);
        for (i, &p) in cloud.iter().enumerate() {
            let sphere = usize::from(i >= first);
            let slack = 1e-5 * (1.0 + centres[sphere].iter().map(|c| c.abs()).sum::<f64>());
            assert!(distance(p, centres[sphere]) <= f64::from(scene.radii[sphere]) + slack);
        }
    }

    #[test]
    fn surface_points_lie_on_their_sphere() {
        let scene = MovingSpheres {
            surface_only: true,
            ..MovingSpheres::default()
        };
        let cloud = scene.generate(3.0).unwrap();
        let [first, _] = scene.counts();
        let centres = scene.centres(3.0);
        for (i, &p) in cloud.iter().enumerate() {
            let sphere = usize::from(i >= first);
            let gap = distance(p, centres[sphere]) - f64::from(scene.radii[sphere]);
            assert!(gap.abs() < 1e-5, "{gap}");
        }
    }

    #[test]
    fn default_silhouettes_sometimes_overlap_from_above() {
        let scene = MovingSpheres::default();
        let reach = f64::from(scene.radii[0] + scene.radii[1]);
        let gaps: Vec<f64> = (0..200)
            .map(|step| {
                let [a, b] = scene.centres(f64::from(step) * 4.0 * PI / 200.0);
                (a[0] - b[0]).hypot(a[1] - b[1]) - reach
            })
            .collect();
        assert!(gaps.iter().any(|&g| g < 0.0), "never overlap");
        assert!(gaps.iter().any(|&g| g > 0.0), "always overlap");
    }

    #[test]
    fn bad_parameters_are_errors_naming_them() {
        let base = MovingSpheres::default();
        let cases = [
            (
                MovingSpheres {
                    points: 0,
                    ..base.clone()
                },
                "points",
            ),
            (
                MovingSpheres {
                    radii: [0.0, 1.0],
                    ..base.clone()
                },
                "radii[0]",
            ),
            (
                MovingSpheres {
                    radii: [1.0, -2.0],
                    ..base.clone()
                },
                "radii[1]",
            ),
            (
                MovingSpheres {
                    radii: [f32::NAN, 1.0],
                    ..base.clone()
                },
                "radii[0]",
            ),
            (
                MovingSpheres {
                    split: 1.5,
                    ..base.clone()
                },
                "split",
            ),
        ];
        for (scene, name) in cases {
            let err = scene.generate(0.0).unwrap_err();
            assert!(err.to_string().contains(name), "{err}");
        }
        let mut bad_path = base.clone();
        bad_path.paths[1].amplitude[0] = f64::INFINITY;
        assert!(bad_path
            .generate(0.0)
            .unwrap_err()
            .to_string()
            .contains("paths[1].amplitude[0]"));
        assert!(base
            .generate(f64::NAN)
            .unwrap_err()
            .to_string()
            .contains("time"));
    }

    #[test]
    fn config_round_trips_through_json_with_defaults() {
        let scene = MovingSpheres {
            seed: 9,
            ..MovingSpheres::default()
        };
        let json = serde_json::to_string(&scene).unwrap();
        assert_eq!(serde_json::from_str::<MovingSpheres>(&json).unwrap(), scene);
        let partial: MovingSpheres = serde_json::from_str(r#"{"points": 5}"#).unwrap();
        assert_eq!(
            partial,
            MovingSpheres {
                points: 5,
                ..MovingSpheres::default()
            }
        );
    }
}
