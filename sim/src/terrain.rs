//! A scattered height-field scene: smooth hills (where splines fit well) plus sharp
//! cliffs (the steep jumps where the paper warns of Gibbs overshoot).

use crate::error::{
    check_finite, check_finite_all, check_non_negative, check_points, check_positive,
    check_rectangle, SceneError,
};
use crate::sampling::{stream_rng, symmetric, uniform};
use serde::{Deserialize, Serialize};

/// Stream tag separating this scene's random numbers from the other scenes'.
const STREAM_TAG: u64 = 0x5445_5252_4149_4E21; // "TERRAIN!"

/// A Gaussian bump `height * exp(-d^2 / (2 width^2))`; a negative height is a valley.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Hill {
    /// Position of the peak in the xy plane.
    pub centre: [f64; 2],
    /// Peak height (negative for a valley).
    pub height: f64,
    /// Standard deviation of the bump, > 0.
    pub width: f64,
}

/// A step of `rise` on the side of the line through `through` that `normal`
/// points to: a discontinuity in the height field. Skew normals make the jump
/// cross the spline grid diagonally.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Cliff {
    /// Any point on the cliff line.
    pub through: [f64; 2],
    /// Direction (not necessarily unit, non-zero) towards the raised side.
    pub normal: [f64; 2],
    /// Height added on the raised side (negative for a drop).
    pub rise: f64,
}

/// Points `(x, y, h(x, y) + noise)` at uniformly random `(x, y)` in the rectangle
/// `[min, max]`, where `h` sums the hills and cliffs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Terrain {
    /// Number of points sampled (the scan resolution).
    pub points: usize,
    /// Lower-left corner of the sampled rectangle.
    pub min: [f64; 2],
    /// Upper-right corner of the sampled rectangle.
    pub max: [f64; 2],
    /// Smooth features.
    pub hills: Vec<Hill>,
    /// Sharp features.
    pub cliffs: Vec<Cliff>,
    /// Amplitude of uniform height noise in `[-noise, noise]`, >= 0 (scanner jitter).
    pub noise: f64,
    /// Seed of the random stream; fixes the cloud exactly.
    pub seed: u64,
}

impl Default for Terrain {
    /// Three hills (one a valley), a cliff skew to the axes at 30 degrees and an
    /// axis-aligned one, and a little noise, over an 8 x 6 rectangle.
    fn default() -> Self {
        let skew = 30f64.to_radians();
        Self {
            points: 30_000,
            min: [-4.0, -3.0],
            max: [4.0, 3.0],
            hills: vec![
                Hill {
                    centre: [-1.5, -1.0],
                    height: 1.0,
                    width: 1.2,
                },
                Hill {
                    centre: [2.0, 1.0],
                    height: 0.6,
                    width: 0.8,
                },
                Hill {
                    centre: [0.5, 2.0],
                    height: -0.4,
                    width: 1.0,
                },
            ],
            cliffs: vec![
                Cliff {
                    through: [0.5, 0.0],
                    normal: [skew.cos(), skew.sin()],
                    rise: 0.8,
                },
                Cliff {
                    through: [-2.5, 0.0],
                    normal: [-1.0, 0.0],
                    rise: 0.5,
                },
            ],
            noise: 0.01,
            seed: 0,
        }
    }
}

impl Hill {
    fn height_at(&self, x: f64, y: f64) -> f64 {
        let d2 = (x - self.centre[0]).powi(2) + (y - self.centre[1]).powi(2);
        self.height * (-d2 / (2.0 * self.width * self.width)).exp()
    }
}

impl Cliff {
    /// The raised side includes the line itself, so the step is well defined.
    fn height_at(&self, x: f64, y: f64) -> f64 {
        let side = (x - self.through[0]) * self.normal[0] + (y - self.through[1]) * self.normal[1];
        if side >= 0.0 {
            self.rise
        } else {
            0.0
        }
    }
}

impl Terrain {
    /// Noise-free ground-truth height at `(x, y)` (defined everywhere, not only
    /// inside the rectangle).
    pub fn height(&self, x: f64, y: f64) -> f64 {
        let hills: f64 = self.hills.iter().map(|h| h.height_at(x, y)).sum();
        let cliffs: f64 = self.cliffs.iter().map(|c| c.height_at(x, y)).sum();
        hills + cliffs
    }

    /// Checks every parameter; `generate` calls this first.
    pub fn validate(&self) -> Result<(), SceneError> {
        check_points("points", self.points)?;
        check_rectangle("rectangle", self.min, self.max)?;
        check_non_negative("noise", self.noise)?;
        self.hills.iter().enumerate().try_for_each(|(i, hill)| {
            check_finite_all(&format!("hills[{i}].centre"), &hill.centre)?;
            check_finite(&format!("hills[{i}].height"), hill.height)?;
            check_positive(&format!("hills[{i}].width"), hill.width)
        })?;
        self.cliffs
            .iter()
            .enumerate()
            .try_for_each(|(i, cliff)| validate_cliff(i, cliff))
    }

    /// The scattered cloud. Heights are evaluated at the f32-rounded `(x, y)` that
    /// is emitted, so a point next to a cliff never lands on the wrong side.
    pub fn generate(&self) -> Result<Vec<[f32; 3]>, SceneError> {
        self.validate()?;
        let mut rng = stream_rng(self.seed, &[STREAM_TAG]);
        let cloud = (0..self.points)
            .map(|_| {
                let x = uniform(&mut rng, self.min[0], self.max[0]) as f32;
                let y = uniform(&mut rng, self.min[1], self.max[1]) as f32;
                let z = self.height(f64::from(x), f64::from(y)) + symmetric(&mut rng, self.noise);
                [x, y, z as f32]
            })
            .collect();
        Ok(cloud)
    }
}

/// A cliff needs a finite line, a non-zero normal and a finite rise.
fn validate_cliff(index: usize, cliff: &Cliff) -> Result<(), SceneError> {
    let name = format!("cliffs[{index}]");
    check_finite_all(&format!("{name}.through"), &cliff.through)?;
    check_finite_all(&format!("{name}.normal"), &cliff.normal)?;
    check_finite(&format!("{name}.rise"), cliff.rise)?;
    if cliff.normal == [0.0, 0.0] {
        return Err(SceneError::Degenerate {
            parameter: format!("{name}.normal"),
            reason: "the normal must be non-zero",
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_seed_gives_same_points() {
        let terrain = Terrain::default();
        assert_eq!(terrain.generate().unwrap(), terrain.generate().unwrap());
        let other = Terrain {
            seed: 1,
            ..Terrain::default()
        };
        assert_ne!(terrain.generate().unwrap(), other.generate().unwrap());
    }

    #[test]
    fn point_count_is_exact() {
        for points in [1, 2, 999, 30_000] {
            let terrain = Terrain {
                points,
                ..Terrain::default()
            };
            assert_eq!(terrain.generate().unwrap().len(), points);
        }
    }

    #[test]
    fn points_lie_on_the_height_field_inside_the_rectangle() {
        let terrain = Terrain::default();
        for [x, y, z] in terrain.generate().unwrap() {
            let (x, y, z) = (f64::from(x), f64::from(y), f64::from(z));
            assert!((terrain.min[0]..=terrain.max[0]).contains(&x));
            assert!((terrain.min[1]..=terrain.max[1]).contains(&y));
            let h = terrain.height(x, y);
            assert!(
                (z - h).abs() <= terrain.noise + 1e-6 * (1.0 + h.abs()),
                "{z} vs {h}"
            );
        }
    }

    #[test]
    fn noise_free_points_sit_exactly_on_the_field() {
        let terrain = Terrain {
            noise: 0.0,
            ..Terrain::default()
        };
        for [x, y, z] in terrain.generate().unwrap() {
            let h = terrain.height(f64::from(x), f64::from(y));
            assert_eq!(z, h as f32);
        }
    }

    #[test]
    fn cliffs_are_sharp_steps() {
        let terrain = Terrain {
            hills: vec![],
            ..Terrain::default()
        };
        let cliff = terrain.cliffs[0];
        let [nx, ny] = cliff.normal;
        let [px, py] = cliff.through;
        let step = terrain.height(px + 1e-9 * nx, py + 1e-9 * ny)
            - terrain.height(px - 1e-9 * nx, py - 1e-9 * ny);
        assert!((step - cliff.rise).abs() < 1e-12);
    }

    #[test]
    fn bad_parameters_are_errors_naming_them() {
        let base = Terrain::default();
        let mut bad_width = base.clone();
        bad_width.hills[1].width = 0.0;
        let mut bad_normal = base.clone();
        bad_normal.cliffs[0].normal = [0.0, 0.0];
        let mut bad_rise = base.clone();
        bad_rise.cliffs[1].rise = f64::NAN;
        let cases = [
            (
                Terrain {
                    points: 0,
                    ..base.clone()
                },
                "points",
            ),
            (
                Terrain {
                    max: [-4.0, 3.0],
                    ..base.clone()
                },
                "rectangle",
            ),
            (
                Terrain {
                    min: [f64::NEG_INFINITY, 0.0],
                    ..base.clone()
                },
                "rectangle.min[0]",
            ),
            (
                Terrain {
                    noise: -0.1,
                    ..base.clone()
                },
                "noise",
            ),
            (bad_width, "hills[1].width"),
            (bad_normal, "cliffs[0].normal"),
            (bad_rise, "cliffs[1].rise"),
        ];
        for (terrain, name) in cases {
            let err = terrain.generate().unwrap_err();
            assert!(err.to_string().contains(name), "{name}: {err}");
        }
    }

    #[test]
    fn config_round_trips_through_json() {
        let terrain = Terrain {
            seed: 4,
            ..Terrain::default()
        };
        let json = serde_json::to_string(&terrain).unwrap();
        assert_eq!(serde_json::from_str::<Terrain>(&json).unwrap(), terrain);
    }
}
