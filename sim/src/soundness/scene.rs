//! Drawing a random soundness scene from a seed: moving solids on and above
//! the floor, sensors above them with their scan times, pipeline delays,
//! transits and fit settings, and which arm reaches in.

use super::arms::ArmKind;
use super::sensors::{FieldOfView, Projection, Sensor};
use super::solids::{Body, Solid};
use super::SoundnessParams;
use glam::{DQuat, DVec3};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use shroud_surrogate::Sides;
use std::f64::consts::{PI, SQRT_2};
use std::fmt;

/// One sensor, its data's trip to the guard, and how its cloud is fitted.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SensorSetup {
    pub sensor: Sensor,
    /// Time in the fit node and upstream before publication (s).
    pub pipeline: f64,
    /// Publication to the guard's callback (s).
    pub transit: f64,
    pub cols: usize,
    pub rows: usize,
    pub sides: Sides,
}

impl SensorSetup {
    /// When the guard received the view (scene clock, s).
    pub fn arrival(&self) -> f64 {
        self.sensor.time + self.pipeline + self.transit
    }
}

/// A drawn scene.
#[derive(Debug, Clone, PartialEq)]
pub struct SoundnessScene {
    pub seed: u64,
    pub solids: Vec<Solid>,
    pub sensors: Vec<SensorSetup>,
    pub arm: ArmKind,
}

/// Largest tilt of a sensor's look from straight down.
const MAX_TILT: f64 = 40.0 * PI / 180.0;

/// A uniformly random unit vector.
fn unit(rng: &mut Pcg64) -> DVec3 {
    let z: f64 = rng.random_range(-1.0..=1.0);
    let phi: f64 = rng.random_range(0.0..2.0 * PI);
    let r = (1.0 - z * z).max(0.0).sqrt();
    DVec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// How far below its centre a body reaches (so that it can rest on z = 0).
fn depth_below_centre(body: &Body) -> f64 {
    match *body {
        Body::Sphere { radius } => radius,
        Body::Cuboid { half, rotation } => {
            // Support of the box in -z: the sum over its axes.
            (0..3)
                .map(|k| {
                    let mut e = DVec3::ZERO;
                    e[k] = 1.0;
                    (rotation * e).z.abs() * half[k]
                })
                .sum()
        }
        Body::Capsule {
            half_length,
            axis,
            radius,
        } => axis.z.abs() * half_length + radius,
    }
}

/// A sphere (r 0.05–0.35 m), a box (half extents 0.03–0.3 m, axis-aligned
/// or rotated) or a capsule (half length 0.05–0.4 m, r 0.03–0.15 m), a third
/// each.
pub(super) fn random_body(rng: &mut Pcg64) -> Body {
    match rng.random_range(0..3) {
        0 => Body::Sphere {
            radius: rng.random_range(0.05..0.35),
        },
        1 => Body::Cuboid {
            half: DVec3::new(
                rng.random_range(0.03..0.3),
                rng.random_range(0.03..0.3),
                rng.random_range(0.03..0.3),
            ),
            rotation: if rng.random_bool(0.5) {
                DQuat::IDENTITY
            } else {
                DQuat::from_axis_angle(unit(rng), rng.random_range(0.0..PI))
            },
        },
        _ => Body::Capsule {
            half_length: rng.random_range(0.05..0.4),
            axis: unit(rng),
            radius: rng.random_range(0.03..0.15),
        },
    }
}

fn random_solid(rng: &mut Pcg64, params: &SoundnessParams) -> Solid {
    let max_speed = params.max_obstacle_speed;
    let body = random_body(rng);
    let resting = rng.random_bool(0.6);
    let z = depth_below_centre(&body)
        + if resting {
            0.0
        } else {
            rng.random_range(0.0..0.8)
        };
    let centre = DVec3::new(rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0), z);
    // Resting solids slide on the floor; floating ones move any way.
    let mut direction = unit(rng);
    if resting {
        direction.z = 0.0;
        direction = direction.normalize_or(DVec3::X);
    }
    let speed = if max_speed > 0.0 {
        rng.random_range(0.0..=max_speed)
    } else {
        0.0
    };
    Solid {
        body,
        centre,
        velocity: direction * speed,
        black: rng.random_bool(params.black_share),
    }
}

fn random_sensor(rng: &mut Pcg64, params: &SoundnessParams) -> SensorSetup {
    let phi = rng.random_range(0.0..2.0 * PI);
    let rho = rng.random_range(0.3..2.0);
    let origin = DVec3::new(rho * phi.cos(), rho * phi.sin(), rng.random_range(1.5..3.0));
    let target = DVec3::new(
        rng.random_range(-0.8..0.8),
        rng.random_range(-0.8..0.8),
        0.0,
    );
    let mut look = (target - origin).normalize();
    if look.angle_between(-DVec3::Z) > MAX_TILT {
        let level = DVec3::new(look.x, look.y, 0.0).normalize_or(DVec3::X);
        look = -DVec3::Z * MAX_TILT.cos() + level * MAX_TILT.sin();
    }
    let deg = |lo: f64, hi: f64, rng: &mut Pcg64| rng.random_range(lo..hi) * PI / 180.0;
    let fov = if rng.random_bool(0.5) {
        FieldOfView::Cone {
            half_angle: deg(20.0, 50.0, rng),
        }
    } else {
        FieldOfView::Frustum {
            half_x: deg(20.0, 50.0, rng),
            half_y: deg(20.0, 50.0, rng),
        }
    };
    let max_range = rng.random_range(2.0..4.5);
    // Aim for a sampling margin of 1 to 3 cm; a ray budget coarsens it.
    let wanted_margin = rng.random_range(0.01..0.03);
    let mut step = wanted_margin / (max_range * SQRT_2);
    let budget = params.max_rays as f64;
    step = step.max((fov.image_area() / budget).sqrt());
    let time = rng.random_range(0.0..0.3);
    let mut sensor = Sensor::new(origin, look, fov, max_range, step, time);
    if params.parallel_rays {
        // Spaced as the perspective rays are where the look meets the floor.
        sensor.projection = Projection::Parallel {
            reference: origin.z / -look.z,
        };
    }
    while sensor.ray_count() > params.max_rays {
        sensor.step *= 1.02;
    }
    let transit = if rng.random_bool(0.85) {
        rng.random_range(0.0..0.1)
    } else {
        rng.random_range(0.1..0.6)
    };
    SensorSetup {
        sensor,
        pipeline: rng.random_range(0.005..0.08),
        transit,
        cols: rng.random_range(8..=32),
        rows: rng.random_range(8..=32),
        sides: if rng.random_bool(params.sandwich_share) {
            Sides::Sandwich
        } else {
            Sides::Upper
        },
    }
}

impl SoundnessScene {
    /// The scene of `seed` (the same seed, the same scene).
    pub fn draw(params: &SoundnessParams, seed: u64) -> Self {
        let mut rng = Pcg64::seed_from_u64(seed);
        let solids = (0..rng.random_range(1..=6))
            .map(|_| random_solid(&mut rng, params))
            .collect();
        let sensors = (0..rng.random_range(1..=4))
            .map(|_| random_sensor(&mut rng, params))
            .collect();
        let arm = if rng.random_bool(0.5) {
            ArmKind::Demo
        } else {
            ArmKind::Urdf
        };
        Self {
            seed,
            solids,
            sensors,
            arm,
        }
    }
}

impl fmt::Display for SoundnessScene {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "scene seed {:#x}, arm {:?}", self.seed, self.arm)?;
        for (k, s) in self.solids.iter().enumerate() {
            writeln!(
                f,
                "  solid {k}: {:?} centre {:.3?} velocity {:.3?}{}",
                s.body,
                s.centre.to_array(),
                s.velocity.to_array(),
                if s.black { " black" } else { "" }
            )?;
        }
        for (k, s) in self.sensors.iter().enumerate() {
            let o = &s.sensor;
            writeln!(
                f,
                "  sensor {k}: {} scan {:.3} s pipeline {:.3} s transit {:.3} s grid {}x{} {:?}",
                o.describe(),
                o.time,
                s.pipeline,
                s.transit,
                s.cols,
                s.rows,
                s.sides
            )?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scenes_are_seeded_and_within_their_bounds() {
        let params = SoundnessParams::default();
        assert_eq!(
            SoundnessScene::draw(&params, 7),
            SoundnessScene::draw(&params, 7)
        );
        for seed in 0..40 {
            let scene = SoundnessScene::draw(&params, seed);
            assert!((1..=6).contains(&scene.solids.len()));
            assert!((1..=4).contains(&scene.sensors.len()));
            for s in &scene.solids {
                assert!(s.velocity.length() <= params.max_obstacle_speed + 1e-12);
                // On or above the floor.
                assert!(s.centre.z - depth_below_centre(&s.body) >= -1e-12);
            }
            for s in &scene.sensors {
                assert!(s.sensor.ray_count() <= params.max_rays);
                assert!(s.sensor.look.angle_between(-DVec3::Z) <= MAX_TILT + 1e-9);
                assert!((8..=32).contains(&s.cols) && (8..=32).contains(&s.rows));
            }
        }
    }
}
