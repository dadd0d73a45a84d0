//! Brute force against forward kinematics: the lever arms bound every shape
//! point's speed in random chains and poses, and the scale keeps `S_p`.

use super::*;
use crate::{ArmModel, Joint, JointKind, Link, Shape};
use glam::{DAffine3, DVec3};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

fn random_arm(rng: &mut Pcg64) -> ArmModel {
    let n = rng.random_range(1..=6);
    let mut links = Vec::new();
    let mut joints = Vec::new();
    let v3 = |rng: &mut Pcg64, s: f64| {
        DVec3::new(
            rng.random_range(-s..s),
            rng.random_range(-s..s),
            rng.random_range(-s..s),
        )
    };
    for i in 0..=n {
        let shapes = if rng.random_bool(0.5) {
            vec![Shape::sphere(v3(rng, 0.3), rng.random_range(0.02..0.1))]
        } else {
            vec![Shape::capsule(
                v3(rng, 0.3),
                v3(rng, 0.3),
                rng.random_range(0.02..0.1),
            )]
        };
        links.push(Link {
            name: format!("l{i}"),
            shapes,
        });
        if i < n {
            let kind = match rng.random_range(0..6) {
                0 => JointKind::Prismatic,
                1 => JointKind::Fixed,
                _ => JointKind::Revolute,
            };
            let limits = (kind == JointKind::Prismatic).then_some([-0.3, 0.4]);
            let axis = v3(rng, 1.0) + DVec3::new(0.0, 0.0, 0.01);
            let xyz = v3(rng, 0.4).to_array();
            let rpy = v3(rng, 3.0).to_array();
            joints.push(
                Joint::new(&format!("j{i}"), kind, axis.to_array(), xyz, rpy, limits).unwrap(),
            );
        }
    }
    ArmModel::new("random", DAffine3::IDENTITY, links, joints).unwrap()
}

/// Points of a world shape: its centre or end points pushed out by the
/// radius along a fixed set of directions.
fn surface_points(shape: &Shape) -> Vec<DVec3> {
    let (cores, r) = match shape {
        Shape::Sphere(s) => (vec![s.centre], s.radius),
        Shape::Capsule(c) => (vec![c.a, c.b, 0.5 * (c.a + c.b)], c.radius),
    };
    let dirs = [
        DVec3::X,
        DVec3::Y,
        DVec3::Z,
        -DVec3::X,
        -DVec3::Y,
        -DVec3::Z,
    ];
    cores
        .iter()
        .flat_map(|&c| dirs.iter().map(move |&d| c + r * d))
        .collect()
}

#[test]
fn lever_arms_bound_every_point_speed_in_random_chains() {
    let mut rng = Pcg64::seed_from_u64(15066);
    let mut worst = 0.0f64;
    for _ in 0..400 {
        let arm = random_arm(&mut rng);
        let levers = LeverArms::new(&arm).unwrap();
        let dof = arm.dof();
        for _ in 0..10 {
            let q: Vec<f64> = (0..dof).map(|_| rng.random_range(-0.3..0.4)).collect();
            let qd: Vec<f64> = (0..dof).map(|_| rng.random_range(-1.0..1.0)).collect();
            let h = 1e-6;
            let ahead: Vec<f64> = q.iter().zip(&qd).map(|(a, b)| a + h * b).collect();
            let (p0, p1) = (arm.forward(&q).unwrap(), arm.forward(&ahead).unwrap());
            for (s0, s1) in p0.shapes.iter().zip(&p1.shapes) {
                let bound: f64 = levers
                    .of_link(s0.link)
                    .iter()
                    .zip(&qd)
                    .map(|(l, v)| l * v.abs())
                    .sum();
                for (a, b) in surface_points(&s0.shape)
                    .iter()
                    .zip(surface_points(&s1.shape))
                {
                    let speed = (b - *a).length() / h;
                    assert!(speed <= bound * (1.0 + 1e-6) + 1e-9, "{speed} > {bound}");
                    worst = worst.max(speed / bound.max(1e-12));
                }
            }
        }
    }
    // The bound is not vacuous: some point comes within a few tens of percent.
    assert!(worst > 0.3, "loosest ratio {worst}");
}

fn two_link_arm() -> ArmModel {
    ArmFile::from_toml_str(
        r#"
        [[links]]
        name = "base"
        [[links]]
        name = "upper"
        capsules = [{ a = [0.0, 0.0, 0.0], b = [0.5, 0.0, 0.0], radius = 0.05 }]
        [[links]]
        name = "fore"
        capsules = [{ a = [0.0, 0.0, 0.0], b = [0.4, 0.0, 0.0], radius = 0.04 }]
        [[joints]]
        name = "shoulder"
        kind = "revolute"
        axis = [0.0, 0.0, 1.0]
        [[joints]]
        name = "elbow"
        kind = "revolute"
        xyz = [0.5, 0.0, 0.0]
        axis = [0.0, 0.0, 1.0]
        "#,
    )
    .unwrap()
    .arm
}

use crate::ArmFile;

fn motion(decel: f64) -> ArmMotion {
    ArmMotion {
        reaction_time: 0.1,
        position_uncertainty: 0.01,
        scale_rise_per_second: 1.0,
        joints: vec![
            JointMotion {
                max_velocity: 1.0,
                stopping: StoppingModel::Deceleration(decel),
            };
            2
        ],
    }
}

#[test]
fn the_scale_grows_with_clearance_and_keeps_the_protective_distance() {
    let arm = two_link_arm();
    let monitor = SpeedMonitor::new(&arm, motion(5.0)).unwrap();
    let timing = Timing {
        horizon: 0.1,
        obstacle_speed: 1.6,
    };
    let speeds = monitor.current_speeds(None, 0.0).unwrap();
    assert_eq!(speeds, vec![0.0, 0.0]);
    let now = MotionNow {
        speeds: &speeds,
        joint_state_age: 0.0,
    };
    let stop = 0.05;
    let mut previous = -1.0;
    for k in 0..200 {
        let c = k as f64 * 0.01;
        let s = monitor.scale(&[c, c, c], stop, &now, &timing);
        assert!(
            s.scale >= previous,
            "scale fell from {previous} at clearance {c}"
        );
        previous = s.scale;
        if s.scale > 0.0 {
            // Every link keeps S_p at the chosen scale.
            for link in 0..3 {
                let levers = LeverArms::new(&arm).unwrap();
                let need = protective(monitor.motion(), &levers, link, &now, &timing, s.scale);
                assert!(c >= stop + need.total() - 1e-12);
            }
        }
    }
    assert_eq!(previous, 1.0);
    // Standing still, a moving link still needs the obstacle's travel while
    // the arm reacts; the base, which no joint moves, the stop distance and
    // Z_r alone.
    let s = monitor.scale(&[0.07, 0.05 + 0.16, 1.0], stop, &now, &timing);
    assert_eq!((s.scale, s.limiting_link), (0.0, Some(1)));
    assert!((s.protective_distance - (0.05 + 0.16 + 0.01)).abs() < 1e-12);
    let base = monitor.scale(&[0.059, 1.0, 1.0], stop, &now, &timing);
    assert_eq!((base.scale, base.limiting_link), (0.0, Some(0)));
    assert!(monitor.scale(&[0.061, 1.0, 1.0], stop, &now, &timing).scale > 0.0);
}

#[test]
fn a_fast_arm_must_slow_first_and_an_arm_over_its_limit_is_refused() {
    let arm = two_link_arm();
    let monitor = SpeedMonitor::new(&arm, motion(2.0)).unwrap();
    let over = monitor.current_speeds(Some(&[0.2, 1.2]), 0.0).unwrap_err();
    assert_eq!((over.joint, over.speed), (1, 1.2));
    let timing = Timing {
        horizon: 0.1,
        obstacle_speed: 0.0,
    };
    let still = vec![0.0, 0.0];
    let moving = monitor.current_speeds(Some(&[1.0, 1.0]), 0.0).unwrap();
    let at = |speeds: &[f64]| {
        monitor.scale(
            &[1.0, 0.6, 0.6],
            0.05,
            &MotionNow {
                speeds,
                joint_state_age: 0.0,
            },
            &timing,
        )
    };
    let (calm, rushed) = (at(&still), at(&moving));
    assert!(calm.scale > rushed.scale, "{calm:?} {rushed:?}");
    assert_eq!(rushed.limiting_link, Some(2));
}

#[test]
fn a_measured_stop_that_forbids_any_motion_reports_what_motion_needs() {
    let arm = two_link_arm();
    let table = StoppingModel::Measured(vec![StopSample {
        fraction: 1.0,
        distance: 0.2,
        time: 0.2,
    }]);
    let mut m = motion(5.0);
    m.joints[0].stopping = table.clone();
    m.joints[1].stopping = table;
    let monitor = SpeedMonitor::new(&arm, m).unwrap();
    let timing = Timing {
        horizon: 0.0,
        obstacle_speed: 0.0,
    };
    let still = [0.0, 0.0];
    let now = MotionNow {
        speeds: &still,
        joint_state_age: 0.0,
    };
    // Standing still needs C + Z_r = 0.06; any motion a 0.2 rad stop on
    // each joint, times the levers.
    let s = monitor.scale(&[1.0, 1.0, 0.1], 0.05, &now, &timing);
    assert_eq!(s.scale, 0.0);
    assert!(s.protective_distance > 0.1, "{s:?}");
    assert_eq!(s.limiting_link, Some(2));
}

#[test]
fn a_missing_or_bad_motion_table_is_named() {
    let arm = two_link_arm();
    let mut m = motion(2.0);
    m.joints.pop();
    let e = SpeedMonitor::new(&arm, m).unwrap_err().to_string();
    assert!(e.contains("1 joint entries for 2 actuated joints"), "{e}");
    let mut m = motion(2.0);
    m.reaction_time = f64::NAN;
    assert!(SpeedMonitor::new(&arm, m)
        .unwrap_err()
        .to_string()
        .contains("reaction_time"));
    let mut m = motion(2.0);
    m.joints[1].max_velocity = 0.0;
    assert!(SpeedMonitor::new(&arm, m)
        .unwrap_err()
        .to_string()
        .contains("'elbow'"));
}

/// `S_p` never shrinks as the scale grows, for random stopping models
/// (constant decelerations and measured tables), current speeds and
/// timings: so every scale below a feasible one is feasible, which the rise
/// limit relies on.
#[test]
fn the_protective_distance_grows_with_the_scale() {
    let mut rng = Pcg64::seed_from_u64(10218);
    let arm = two_link_arm();
    let levers = LeverArms::new(&arm).unwrap();
    for _ in 0..2000 {
        let mut joint = || {
            let max_velocity = rng.random_range(0.2..3.0);
            let stopping = if rng.random_bool(0.5) {
                StoppingModel::Deceleration(rng.random_range(0.5..20.0))
            } else {
                let (mut d, mut t) = (0.0, 0.0);
                let mut fractions: Vec<f64> = (0..rng.random_range(0..4))
                    .map(|_| rng.random_range(0.05..0.95))
                    .collect();
                fractions.sort_by(f64::total_cmp);
                fractions.dedup();
                fractions.push(1.0);
                StoppingModel::Measured(
                    fractions
                        .into_iter()
                        .map(|fraction| {
                            d += rng.random_range(0.0..0.2);
                            t += rng.random_range(0.0..0.2);
                            StopSample {
                                fraction,
                                distance: d,
                                time: t,
                            }
                        })
                        .collect(),
                )
            };
            JointMotion {
                max_velocity,
                stopping,
            }
        };
        let joints = vec![joint(), joint()];
        let speeds: Vec<f64> = joints
            .iter()
            .map(|j| rng.random_range(0.0..1.05) * j.max_velocity)
            .collect();
        let motion = ArmMotion {
            reaction_time: rng.random_range(0.0..0.2),
            position_uncertainty: 0.0,
            scale_rise_per_second: 1.0,
            joints,
        };
        let now = MotionNow {
            speeds: &speeds,
            joint_state_age: rng.random_range(0.0..0.1),
        };
        let timing = Timing {
            horizon: rng.random_range(0.0..0.3),
            obstacle_speed: rng.random_range(0.0..2.0),
        };
        for link in 0..3 {
            let mut previous = 0.0;
            for k in 0..=100 {
                let s = k as f64 / 100.0;
                let need = protective(&motion, &levers, link, &now, &timing, s).total();
                assert!(
                    need >= previous - 1e-12,
                    "{motion:?} {speeds:?} link {link} at {s}: {need} < {previous}"
                );
                previous = need;
            }
        }
    }
}
