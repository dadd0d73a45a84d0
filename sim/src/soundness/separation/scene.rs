//! Drawing one separation trajectory from its seed: the arm and its motion
//! limits, its trajectory, the solids and the person crossing its
//! workspace, the sensors and their scans' delays, and the timing of every
//! joint state, decision and verdict.

use super::super::arms::{random_configuration, ArmKind, Arms};
use super::super::scene::random_body;
use super::super::sensors::{FieldOfView, Projection, Sensor};
use super::super::solids::{Body, Solid};
use super::super::SoundnessError;
use super::reference::Reference;
use super::SeparationParams;
use glam::{DAffine3, DVec2, DVec3};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use shroud_guard::{
    ArmModel, ArmMotion, Deadman, JointKind, JointMotion, Shape, StopSample, StoppingModel,
};
use shroud_surrogate::Sides;
use std::f64::consts::TAU;
use std::fmt;

/// The two arms of [`Arms`], mounted `lift` higher (so that the floor, which
/// the guard must treat as an obstacle moving at the speed bound, is not
/// always the nearest thing), with a bound on their reach.
#[derive(Debug, Clone)]
pub struct SeparationArms {
    pub demo: ArmModel,
    pub urdf: ArmModel,
    reach: [f64; 2],
}

impl SeparationArms {
    pub fn load(lift: f64) -> Result<Self, SoundnessError> {
        let arms = Arms::load()?;
        let lifted = |arm: &ArmModel| {
            let base = DAffine3::from_translation(DVec3::Z * lift) * *arm.base();
            ArmModel::new(
                arm.name(),
                base,
                arm.links().to_vec(),
                arm.joints().to_vec(),
            )
        };
        let (demo, urdf) = (lifted(&arms.demo)?, lifted(&arms.urdf)?);
        let reach = [reach(&demo), reach(&urdf)];
        Ok(Self { demo, urdf, reach })
    }

    pub fn get(&self, kind: ArmKind) -> &ArmModel {
        match kind {
            ArmKind::Demo => &self.demo,
            ArmKind::Urdf => &self.urdf,
        }
    }

    /// A bound on the distance from any joint's axis to any point of a shape
    /// it moves, in any pose (at least 1, so that it also bounds a prismatic
    /// joint's unit lever): the chain's joint offsets (and prismatic travels)
    /// summed, plus the farthest shape point from its link's origin.
    pub fn reach(&self, kind: ArmKind) -> f64 {
        self.reach[kind as usize]
    }
}

/// See [`SeparationArms::reach`]: written here from the arm's definition.
fn reach(arm: &ArmModel) -> f64 {
    let chain: f64 = arm
        .joints()
        .iter()
        .map(|j| {
            let travel = match (j.kind(), j.limits()) {
                (JointKind::Prismatic, Some(l)) => l.lower.abs().max(l.upper.abs()),
                _ => 0.0,
            };
            j.origin().translation.length() + travel
        })
        .sum();
    let extent = arm
        .links()
        .iter()
        .flat_map(|l| &l.shapes)
        .map(|s| match s {
            Shape::Sphere(s) => s.centre.length() + s.radius,
            Shape::Capsule(c) => c.a.length().max(c.b.length()) + c.radius,
        })
        .fold(0.0, f64::max);
    (chain + extent).max(1.0)
}

/// A sensor that rescans at a fixed rate, and its scans' trips to the guard.
#[derive(Debug, Clone, PartialEq)]
pub struct ScanningSensor {
    /// The sensor; its `time` is set per scan.
    pub sensor: Sensor,
    /// Scans per second, and the time of the first.
    pub rate: f64,
    pub phase: f64,
    pub cols: usize,
    pub rows: usize,
    pub sides: Sides,
    /// Per scan: time in the pipeline before publication, and the transit
    /// from publication to the guard (s).
    pub delays: Vec<(f64, f64)>,
}

impl ScanningSensor {
    pub fn scan_time(&self, k: usize) -> f64 {
        self.phase + k as f64 / self.rate
    }
}

/// What happens to one joint state.
#[derive(Debug, Clone, PartialEq)]
pub struct StateTiming {
    /// From the sample to the guard's decision (s).
    pub guard_delay: f64,
    /// From the decision to the verdict reaching the arm's deadman (s).
    pub transport: f64,
    /// Whether the joint state carries measured velocities.
    pub velocities: bool,
    /// Whether its verdict is lost on the way (the deadman never sees it).
    pub dropped: bool,
    /// Per joint, the error of the reported position (within `Z_r`).
    pub noise: Vec<f64>,
}

/// The timing of the loop: joint states, deadman, reaction.
#[derive(Debug, Clone, PartialEq)]
pub struct LoopTiming {
    /// Joint state period and the first sample's time (s).
    pub period: f64,
    pub phase: f64,
    /// The deadman's deadline after sending a joint state (s, `<= H`).
    pub deadline: f64,
    /// From the deadman's scale to the motion obeying it (s): the
    /// controller's lag. With the longest transport, exactly `T_r` in most
    /// scenes, less in the others.
    pub controller_lag: f64,
    /// The longest transport of a verdict (s).
    pub transport_max: f64,
    /// The share of verdicts lost at random, and an interval in which
    /// every verdict is lost (the guard silent or cut off), if any.
    pub loss: f64,
    pub blackout: Option<(f64, f64)>,
    /// The worst network the deadman allows: every verdict that would slow
    /// the arm (a stop, or a clear at a lower scale than the one it runs
    /// at) is lost, so that it runs on its last clear until the deadline.
    pub slowing_lost: bool,
    pub states: Vec<StateTiming>,
}

impl LoopTiming {
    pub fn sample_time(&self, k: usize) -> f64 {
        self.phase + k as f64 * self.period
    }
}

/// One trajectory's world.
#[derive(Debug, Clone, PartialEq)]
pub struct SeparationScene {
    pub seed: u64,
    pub arm: ArmKind,
    pub solids: Vec<Solid>,
    /// The walking person, an index into `solids`.
    pub person: Option<usize>,
    pub sensors: Vec<ScanningSensor>,
    pub motion: ArmMotion,
    pub reference: Reference,
    pub timing: LoopTiming,
}

/// A uniformly random unit vector.
fn unit(rng: &mut Pcg64) -> DVec3 {
    let z: f64 = rng.random_range(-1.0..=1.0);
    let phi: f64 = rng.random_range(0.0..TAU);
    let r = (1.0 - z * z).max(0.0).sqrt();
    DVec3::new(r * phi.cos(), r * phi.sin(), z)
}

fn horizontal(rng: &mut Pcg64) -> DVec3 {
    let phi: f64 = rng.random_range(0.0..TAU);
    DVec3::new(phi.cos(), phi.sin(), 0.0)
}

fn in_disc(rng: &mut Pcg64, radius: f64) -> DVec2 {
    let r = radius * rng.random_range(0.0f64..1.0).sqrt();
    let phi: f64 = rng.random_range(0.0..TAU);
    DVec2::new(r * phi.cos(), r * phi.sin())
}

/// How far below its centre a body reaches.
fn depth_below_centre(body: &Body) -> f64 {
    match *body {
        Body::Sphere { radius } => radius,
        Body::Cuboid { half, rotation } => (0..3)
            .map(|k| {
                let mut e = DVec3::ZERO;
                e[k] = 1.0;
                (rotation * e).z.abs() * half[k]
            })
            .sum(),
        Body::Capsule {
            half_length,
            axis,
            radius,
        } => axis.z.abs() * half_length + radius,
    }
}

/// The speed of a solid: the bound in three tenths of them, else below it.
fn speed(rng: &mut Pcg64, bound: f64) -> f64 {
    if bound <= 0.0 {
        0.0
    } else if rng.random_bool(0.3) {
        bound
    } else {
        rng.random_range(0.0..bound)
    }
}

/// How far above the arm's mount solids may fly: every sensor's aperture
/// plane (at least 1 m above the mount, tilted by at most 10°) lies above
/// this within 3.4 m of the sensor's axis, so that a sensor always looks at
/// the solids from outside the scene, as the guard's views assume (a solid
/// above a parallel-ray sensor would drop into its columns unseen).
const CEILING_ABOVE_MOUNT: f64 = 0.4;

/// `velocity` with its vertical part cut so that a centre at `at` when
/// `crossing` stays at most `top` high over `[0, duration]`.
fn below(at: DVec3, mut velocity: DVec3, crossing: f64, duration: f64, top: f64) -> DVec3 {
    let room = (top - at.z).max(0.0);
    if velocity.z > 0.0 && duration > crossing {
        velocity.z = velocity.z.min(room / (duration - crossing));
    } else if velocity.z < 0.0 && crossing > 0.0 {
        velocity.z = velocity.z.max(-room / crossing);
    }
    velocity
}

/// A solid that passes a random point of the arm's workspace at a random
/// time: 40 % slide on the floor, the others fly at the arm's height; of
/// these, half are aimed at `aim` (where some shape of the arm is at one of
/// its waypoints, give or take 0.3 m) and a tenth stand still near it.
fn random_solid(rng: &mut Pcg64, params: &SeparationParams, base: DVec3, aim: DVec3) -> Solid {
    let body = random_body(rng);
    let resting = rng.random_bool(0.4);
    let crossing = rng.random_range(0.0..=params.duration);
    let ceiling = base.z + CEILING_ABOVE_MOUNT;
    let reach = Solid {
        body,
        centre: DVec3::ZERO,
        velocity: DVec3::ZERO,
        black: false,
    }
    .bounding_radius();
    if !resting && rng.random_bool(0.5) {
        let mut through = aim + unit(rng) * rng.random_range(0.0..0.3);
        through.z = through.z.min(ceiling - reach);
        let still = rng.random_bool(0.1);
        let bound = if still { 0.0 } else { params.obstacle_speed };
        let velocity = below(
            through,
            unit(rng) * speed(rng, bound),
            crossing,
            params.duration,
            ceiling - reach,
        );
        return Solid {
            body,
            centre: through - velocity * crossing,
            velocity,
            black: false,
        };
    }
    let xy = base.truncate() + in_disc(rng, 1.4);
    let z = if resting {
        depth_below_centre(&body)
    } else {
        rng.random_range(0.8..(base.z - 0.1).max(0.9))
            .min(ceiling - reach)
    };
    let direction = if resting { horizontal(rng) } else { unit(rng) };
    let velocity = below(
        xy.extend(z),
        direction * speed(rng, params.obstacle_speed),
        crossing,
        params.duration,
        ceiling - reach,
    );
    Solid {
        body,
        centre: xy.extend(z) - velocity * crossing,
        velocity,
        black: false,
    }
}

/// A person (a vertical capsule, 1.6 to 1.9 m tall, radius 0.15 to 0.25 m)
/// walking straight across at exactly the speed bound, passing within 0.5 m
/// of `aim` (where the arm reaches lowest at one of its waypoints) at a
/// random time after 0.8 s.
fn person(rng: &mut Pcg64, params: &SeparationParams, aim: DVec3) -> (Solid, f64) {
    let radius = rng.random_range(0.15..0.25);
    let height = rng.random_range(1.6..1.9);
    let direction = horizontal(rng);
    let across = DVec3::new(-direction.y, direction.x, 0.0);
    let closest = aim.truncate().extend(0.5 * height) + across * rng.random_range(-0.5..0.5);
    let crossing = if params.duration > 1.0 {
        rng.random_range(0.8..=params.duration)
    } else {
        rng.random_range(0.0..=params.duration)
    };
    let velocity = direction * params.obstacle_speed;
    let solid = Solid {
        body: Body::Capsule {
            half_length: 0.5 * height - radius,
            axis: DVec3::Z,
            radius,
        },
        centre: closest - velocity * crossing,
        velocity,
        black: false,
    };
    (solid, crossing)
}

/// A sensor 1 to 1.5 m above the arm's mount, within 0.6 m of its axis,
/// looking down (tilted by up to 10°), its footprint on the floor 3.4 to
/// 4.4 m across (parallel rays; perspective: half angles of 40° to 55°),
/// its range just past the floor, its ray grid as fine as `max_rays` allows.
fn random_sensor(rng: &mut Pcg64, params: &SeparationParams, base: DVec3) -> ScanningSensor {
    let origin = (base.truncate() + in_disc(rng, 0.6)).extend(base.z + rng.random_range(1.0..1.5));
    let tilt = rng.random_range(0.0..10f64.to_radians());
    let level = horizontal(rng);
    let look = -DVec3::Z * tilt.cos() + level * tilt.sin();
    let reference = origin.z / tilt.cos();
    let (fov, range) = if params.parallel_rays {
        let half = |rng: &mut Pcg64| (rng.random_range(1.7..2.2) / reference).atan();
        let fov = FieldOfView::Frustum {
            half_x: half(rng),
            half_y: half(rng),
        };
        (fov, reference + 4.4 * tilt.sin() + 0.5)
    } else {
        let deg = |rng: &mut Pcg64| rng.random_range(40f64..55.0).to_radians();
        let fov = if rng.random_bool(0.5) {
            FieldOfView::Cone {
                half_angle: deg(rng),
            }
        } else {
            FieldOfView::Frustum {
                half_x: deg(rng),
                half_y: deg(rng),
            }
        };
        // Past the floor at the edge of the view (55° + 10° from vertical).
        (fov, origin.z / 65f64.to_radians().cos() + 0.3)
    };
    let step = (fov.image_area() / params.max_rays as f64).sqrt();
    let mut sensor = Sensor::new(origin, look, fov, range, step, 0.0);
    if params.parallel_rays {
        sensor.projection = Projection::Parallel { reference };
    }
    while sensor.ray_count() > params.max_rays {
        sensor.step *= 1.02;
    }
    let rate = rng.random_range(params.scan_rate_min..=params.scan_rate_max);
    let phase = rng.random_range(0.0..1.0 / rate);
    let scans = ((params.duration - phase) * rate).floor().max(0.0) as usize + 1;
    let delays = (0..scans)
        .map(|_| {
            let pipeline = rng.random_range(0.005..0.03);
            let transit = if rng.random_bool(0.9) {
                rng.random_range(0.0..0.02)
            } else {
                rng.random_range(0.02..0.15)
            };
            (pipeline, transit)
        })
        .collect();
    ScanningSensor {
        sensor,
        rate,
        phase,
        cols: rng.random_range(12..=24),
        rows: rng.random_range(12..=24),
        sides: if rng.random_bool(params.sandwich_share) {
            Sides::Sandwich
        } else {
            Sides::Upper
        },
        delays,
    }
}

/// A table of measured stops, as a maker would publish it for a brake that
/// engages after `delay` and then decelerates at `a`, padded by up to 20 %.
fn measured_table(rng: &mut Pcg64, max_velocity: f64, a: f64) -> StoppingModel {
    let delay = rng.random_range(0.0..0.04);
    let fractions: &[f64] = if rng.random_bool(0.5) {
        &[1.0 / 3.0, 2.0 / 3.0, 1.0]
    } else {
        &[0.25, 0.5, 0.75, 1.0]
    };
    let pad = rng.random_range(1.0..1.2);
    StoppingModel::Measured(
        fractions
            .iter()
            .map(|&fraction| {
                let v = fraction * max_velocity;
                StopSample {
                    fraction,
                    distance: pad * (v * delay + v * v / (2.0 * a)),
                    time: pad * (delay + v / a),
                }
            })
            .collect(),
    )
}

/// The arm's `[motion]` table: per joint a velocity limit (a per-arm level
/// of 0.3 to 1.2 rad/s times 0.7 to 1.5) and a constant deceleration (a
/// level of 2 to 20 rad/s² times 0.6 to 1.6) or, for two arms in five,
/// measured stops; a reaction time of 0.02 to 0.15 s, a position
/// uncertainty of 0 to 1 cm, a rise limit of 0.5 to 5 per second.
fn random_motion(rng: &mut Pcg64, arm: &ArmModel) -> ArmMotion {
    let speed = rng.random_range(0.3..1.2);
    let decel = rng.random_range(2.0..20.0);
    let tables = rng.random_bool(0.4);
    let joints = (0..arm.dof())
        .map(|_| {
            let max_velocity = speed * rng.random_range(0.7..1.5);
            let a = decel * rng.random_range(0.6..1.6);
            let stopping = if tables {
                measured_table(rng, max_velocity, a)
            } else {
                StoppingModel::Deceleration(a)
            };
            JointMotion {
                max_velocity,
                stopping,
            }
        })
        .collect();
    ArmMotion {
        reaction_time: rng.random_range(0.02..0.15),
        position_uncertainty: rng.random_range(0.0..0.01),
        scale_rise_per_second: if rng.random_bool(0.2) {
            1.0
        } else {
            rng.random_range(0.5..5.0)
        },
        joints,
    }
}

/// The lowest point of the arm's shapes at `q` (`-inf` when `q` is refused).
fn lowest(arm: &ArmModel, q: &[f64]) -> f64 {
    arm.forward(q).map_or(f64::NEG_INFINITY, |pose| {
        pose.shapes
            .iter()
            .map(|s| match s.shape {
                Shape::Sphere(s) => s.centre.z - s.radius,
                Shape::Capsule(c) => c.a.z.min(c.b.z) - c.radius,
            })
            .fold(f64::INFINITY, f64::min)
    })
}

/// A configuration within the limits whose every shape is at least
/// `min_height` above the floor, in seven waypoints in ten also reaching
/// below `min_height + 0.6` (working low, where people are); the best of 64
/// tries otherwise.
fn waypoint(rng: &mut Pcg64, arm: &ArmModel, min_height: f64) -> Vec<f64> {
    let low = rng.random_bool(0.7).then_some(min_height + 0.6);
    let mut best = (f64::INFINITY, Vec::new());
    for _ in 0..64 {
        let q = random_configuration(arm, rng);
        let z = lowest(arm, &q);
        if z >= min_height && low.is_none_or(|top| z <= top) {
            return q;
        }
        // Distance from the band, to keep the nearest miss.
        let miss = (min_height - z).max(low.map_or(0.0, |top| z - top));
        if miss < best.0 {
            best = (miss, q);
        }
    }
    best.1
}

/// The next waypoint after `from`: every joint moved by up to 0.4 to 1.2 s
/// of its velocity limit (so that all of them move at a good part of it),
/// within its limits, every shape at least `min_height` up (the first of 32
/// tries that is; staying put otherwise).
fn step(
    rng: &mut Pcg64,
    arm: &ArmModel,
    from: &[f64],
    limits: &[f64],
    min_height: f64,
) -> Vec<f64> {
    for _ in 0..32 {
        let reach = rng.random_range(0.4..1.2);
        let q: Vec<f64> = arm
            .actuated_joints()
            .zip(from.iter().zip(limits))
            .map(|(joint, (&q, &v))| {
                let to = q + rng.random_range(-1.0..=1.0) * v * reach;
                match joint.limits() {
                    Some(l) => to.clamp(l.lower, l.upper),
                    None => to,
                }
            })
            .collect();
        if lowest(arm, &q) >= min_height {
            return q;
        }
    }
    from.to_vec()
}

/// The lowest shape centre of the arm at a random waypoint of its
/// trajectory.
fn lowest_point(rng: &mut Pcg64, arm: &ArmModel, reference: &Reference) -> DVec3 {
    let k = rng.random_range(0..reference.moves.len().max(1));
    let q = reference
        .moves
        .get(k)
        .map_or_else(|| reference.start().to_vec(), |m| m.to.clone());
    arm.forward(&q)
        .ok()
        .and_then(|pose| {
            pose.shapes
                .iter()
                .map(|s| match s.shape {
                    Shape::Sphere(s) => s.centre,
                    Shape::Capsule(c) => {
                        if c.a.z < c.b.z {
                            c.a
                        } else {
                            c.b
                        }
                    }
                })
                .min_by(|a, b| a.z.total_cmp(&b.z))
        })
        .unwrap_or(arm.base().translation)
}

/// Where a random shape of the arm is at a random waypoint of its
/// trajectory.
fn aim_point(rng: &mut Pcg64, arm: &ArmModel, reference: &Reference) -> DVec3 {
    let k = rng.random_range(0..reference.moves.len().max(1));
    let q = reference
        .moves
        .get(k)
        .map_or_else(|| reference.start().to_vec(), |m| m.to.clone());
    let Ok(pose) = arm.forward(&q) else {
        return arm.base().translation;
    };
    let i = rng.random_range(0..pose.shapes.len().max(1));
    pose.shapes
        .get(i)
        .map_or(arm.base().translation, |s| match s.shape {
            Shape::Sphere(s) => s.centre,
            Shape::Capsule(c) => c.a + (c.b - c.a) * rng.random_range(0.0..=1.0),
        })
}

impl SeparationScene {
    /// The trajectory of `seed` (the same seed, the same trajectory).
    pub fn draw(arms: &SeparationArms, params: &SeparationParams, seed: u64) -> Self {
        let mut rng = Pcg64::seed_from_u64(seed);
        let kind = if rng.random_bool(0.5) {
            ArmKind::Demo
        } else {
            ArmKind::Urdf
        };
        let arm = arms.get(kind);
        let base = arm.base().translation;
        let motion = random_motion(&mut rng, arm);
        let limits: Vec<f64> = motion.joints.iter().map(|j| j.max_velocity).collect();
        let reference =
            Reference::draw(
                &mut rng,
                &limits,
                params.duration + 0.5,
                |rng, from| match from {
                    None => waypoint(rng, arm, params.min_height),
                    Some(from) => step(rng, arm, from, &limits, params.min_height),
                },
            );
        let mut solids = Vec::new();
        for _ in 0..rng.random_range(1..=4) {
            let aim = aim_point(&mut rng, arm, &reference);
            solids.push(random_solid(&mut rng, params, base, aim));
        }
        let walker = rng.random_bool(params.person_share).then(|| {
            let aim = lowest_point(&mut rng, arm, &reference);
            person(&mut rng, params, aim)
        });
        let person_index = walker.as_ref().map(|(solid, _)| {
            solids.push(*solid);
            solids.len() - 1
        });
        let sensors = (0..rng.random_range(1..=2))
            .map(|_| random_sensor(&mut rng, params, base))
            .collect();
        let approach = walker.map(|(_, crossing)| crossing);
        let timing = Self::draw_timing(&mut rng, params, &motion, arms.reach(kind), approach);
        Self {
            seed,
            arm: kind,
            solids,
            person: person_index,
            sensors,
            motion,
            reference,
            timing,
        }
    }

    /// Joint states every `1 / joint_rate` s from a random phase; the
    /// deadman's deadline 0.04 s to `H`; the reaction `T_r` split into a
    /// transport of at most 0.03 s (the longest in three tenths of the
    /// verdicts) and a controller lag (in seven scenes in ten exactly the
    /// rest of `T_r`); guard delays of 0.5 to 8 ms (15 %: up to 40 ms).
    fn draw_timing(
        rng: &mut Pcg64,
        params: &SeparationParams,
        motion: &ArmMotion,
        reach: f64,
        approach: Option<f64>,
    ) -> LoopTiming {
        let period = 1.0 / params.joint_rate;
        let phase = rng.random_range(0.0..period);
        let requested = if rng.random_bool(0.5) {
            params.horizon
        } else {
            rng.random_range(0.04f64.min(params.horizon)..=params.horizon)
        };
        let deadline = Deadman::deadline_for(period, Some(requested), params.horizon)
            .unwrap_or(params.horizon);
        let reaction = motion.reaction_time;
        let transport_max = rng.random_range(0.0..=reaction.min(0.03));
        let controller_lag = if rng.random_bool(0.7) {
            reaction - transport_max
        } else {
            rng.random_range(0.0..=reaction - transport_max)
        };
        let loss = if rng.random_bool(0.4) {
            0.0
        } else {
            rng.random_range(0.0..0.3)
        };
        // With a person, half the blackouts start as the person comes
        // near (0.2 to 0.8 s before passing closest to the mount), when the
        // arm runs on its last clear until its deadline.
        let blackout = match approach {
            Some(crossing) if rng.random_bool(0.5) => {
                let from = (crossing - rng.random_range(0.2..0.8)).max(0.0);
                Some((from, from + rng.random_range(0.1..0.6)))
            }
            _ => rng.random_bool(0.3).then(|| {
                let from = rng.random_range(0.0..params.duration);
                (from, from + rng.random_range(0.1..0.6))
            }),
        };
        let slowing_lost = rng.random_bool(0.25);
        let count = ((params.duration - phase) / period).floor().max(0.0) as usize + 1;
        let dof = motion.joints.len();
        // Each joint off by at most this: their effects on any point (at
        // most `reach` from every axis) add up to at most Z_r.
        let noise = motion.position_uncertainty / (dof.max(1) as f64 * reach);
        let states = (0..count)
            .map(|k| StateTiming {
                guard_delay: if rng.random_bool(0.85) {
                    rng.random_range(0.0005..0.008)
                } else {
                    rng.random_range(0.008..0.04)
                },
                transport: if rng.random_bool(0.3) {
                    transport_max
                } else {
                    rng.random_range(0.0..=transport_max)
                },
                velocities: rng.random_bool(params.velocities_share),
                dropped: rng.random_bool(loss)
                    || blackout.is_some_and(|(from, to)| {
                        (from..to).contains(&(phase + k as f64 * period))
                    }),
                noise: (0..dof)
                    .map(|_| noise * rng.random_range(-1.0..=1.0))
                    .collect(),
            })
            .collect();
        LoopTiming {
            period,
            phase,
            deadline,
            controller_lag,
            transport_max,
            loss,
            blackout,
            slowing_lost,
            states,
        }
    }
}

impl fmt::Display for SeparationScene {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let m = &self.motion;
        writeln!(
            f,
            "trajectory seed {:#x}, arm {:?}, T_r {:.3} s, Z_r {:.4} m, rise {:.2}/s",
            self.seed, self.arm, m.reaction_time, m.position_uncertainty, m.scale_rise_per_second
        )?;
        for (j, joint) in m.joints.iter().enumerate() {
            writeln!(
                f,
                "  joint {j}: max velocity {:.3}, {:?}",
                joint.max_velocity, joint.stopping
            )?;
        }
        let t = &self.timing;
        writeln!(
            f,
            "  joint states every {:.3} s from {:.4} s, deadline {:.3} s, controller lag {:.4} s, transport <= {:.4} s, \
             {:.0} % of verdicts lost, blackout {:?}, slowing verdicts lost: {}",
            t.period,
            t.phase,
            t.deadline,
            t.controller_lag,
            t.transport_max,
            100.0 * t.loss,
            t.blackout,
            t.slowing_lost
        )?;
        for (k, s) in self.solids.iter().enumerate() {
            let who = if self.person == Some(k) {
                " (person)"
            } else {
                ""
            };
            writeln!(
                f,
                "  solid {k}{who}: {:?} centre {:.3?} velocity {:.3?}",
                s.body,
                s.centre.to_array(),
                s.velocity.to_array()
            )?;
        }
        for (k, s) in self.sensors.iter().enumerate() {
            writeln!(
                f,
                "  sensor {k}: {}, {:.1} Hz from {:.3} s, grid {}x{} {:?}",
                s.sensor.describe(),
                s.rate,
                s.phase,
                s.cols,
                s.rows,
                s.sides
            )?;
        }
        write!(
            f,
            "  trajectory: {} moves, {:.2} s nominal",
            self.reference.moves.len(),
            self.reference.length()
        )
    }
}
