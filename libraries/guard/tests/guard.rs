//! The guard's promise, checked by brute force in f64 against every cloud point
//! of real (fitted and certified) surrogates: a reported clearance `c` means no
//! certified point lies within `c` of the shape, so a shape that contains a
//! point reports 0 and stops. Attacked with random arm configurations over the
//! moving-spheres scene and with random spheres and capsules over adversarial
//! clouds (spikes, cliffs, holes, tiny spheres, domain edges, trimmed holes).

/// The clouds, fit options and directions the fitter's own tests draw from.
#[path = "../../surrogate/tests/common/mod.rs"]
mod common;

/// Every test lives in `guard::` so that `cargo test -p shroud-guard --test guard`
/// selects all of them.
mod guard {
    use shroud_surrogate::DomainLocate;

    use super::common::clouds::{cloud, CloudKind};
    use super::common::config::config;
    use super::common::directions::{direction, DirectionKind};
    use glam::DVec3;
    use proptest::prelude::*;
    use proptest::sample::select;
    use rand::{Rng, SeedableRng};
    use rand_pcg::Pcg64;
    use shroud_guard::{
        check_arm, check_shapes, ArmFile, ArmModel, Envelope, GuardConfig, GuardReport, Shape,
        WorldShape,
    };
    use shroud_surrogate::{fit_surrogate, FitOptions, Sides, Surrogate};

    const DEMO_ARM: &str = include_str!("../../../launch/arms/demo_arm.toml");

    /// A small arm for the tests: a prismatic lift, a revolute joint, a fixed
    /// flange, with spheres and a capsule.
    const SMALL_ARM: &str = r#"
    name = "small"
    [base]
    xyz = [0.0, 0.0, 2.0]
    rpy = [3.141592653589793, 0.0, 0.0]
    [[links]]
    name = "mount"
    spheres = [{ centre = [0.0, 0.0, 0.0], radius = 0.1 }]
    [[links]]
    name = "slider"
    capsules = [{ a = [0.0, 0.0, 0.0], b = [0.0, 0.0, 0.6], radius = 0.05 }]
    [[links]]
    name = "arm"
    spheres = [{ centre = [0.0, 0.0, 0.2], radius = 0.08 }, { centre = [0.0, 0.0, 0.4], radius = 0.06 }]
    capsules = [{ a = [0.0, 0.0, 0.4], b = [0.3, 0.0, 0.7], radius = 0.03 }]
    [[links]]
    name = "flange"
    spheres = [{ centre = [0.0, 0.0, 0.05], radius = 0.02 }]
    [[joints]]
    name = "lift"
    kind = "prismatic"
    axis = [0.0, 0.0, 1.0]
    limits = [0.0, 1.0]
    [[joints]]
    name = "swing"
    kind = "revolute"
    xyz = [0.0, 0.0, 0.6]
    axis = [1.0, 0.0, 0.0]
    limits = [-1.5, 1.5]
    [[joints]]
    name = "flange"
    kind = "fixed"
    xyz = [0.0, 0.0, 0.7]
"#;

    fn points_f64(points: &[[f32; 3]]) -> Vec<DVec3> {
        points
            .iter()
            .map(|p| DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64))
            .collect()
    }

    fn fit(
        points: &[[f32; 3]],
        sides: Sides,
        direction: [f64; 3],
        grid: usize,
    ) -> Option<Surrogate> {
        let options = FitOptions {
            cols: grid,
            rows: grid,
            direction,
            sides,
            ..FitOptions::default()
        };
        fit_surrogate(points, &options).ok()
    }

    /// Cloud points whose parameters fall in the surrogate's domain (all of the
    /// fitted cloud; kept explicit, the guard answers for the domain only).
    fn in_domain(sur: &Surrogate, points: &[DVec3]) -> Vec<DVec3> {
        let locator = sur.domain.locator(&sur.frame);
        points
            .iter()
            .copied()
            .filter(|p| {
                let (s, t, _) = locator.locate(*p);
                sur.domain.contains_param(s, t)
            })
            .collect()
    }

    /// What the brute force saw: shapes that contain a point, and shapes checked.
    #[derive(Debug, Default, Clone, Copy)]
    struct Tally {
        hits: usize,
        shapes: usize,
        positive: usize,
    }

    /// The promise for every shape of `report`: no point closer than its clearance,
    /// and a shape containing a point reports 0 and sets `stop`.
    fn assert_conservative(
        shapes: &[WorldShape],
        report: &GuardReport,
        points: &[DVec3],
        context: &str,
    ) -> Tally {
        let mut tally = Tally::default();
        assert_eq!(report.shapes.len(), shapes.len());
        for (i, (shape, result)) in shapes.iter().zip(&report.shapes).enumerate() {
            let c = result.clearance;
            assert!(
                c >= 0.0 && c.is_finite(),
                "{context}: shape {i} clearance {c}"
            );
            let (closest, at) = points
                .iter()
                .map(|p| (shape.shape.distance_to(*p), *p))
                .fold(
                    (f64::INFINITY, DVec3::ZERO),
                    |a, b| if b.0 < a.0 { b } else { a },
                );
            assert!(
            closest.max(0.0) >= c,
            "{context}: shape {i} {:?} reports clearance {c} but point {at:?} is {closest} away",
            shape.shape
        );
            // The bound to the occupied space seen alone holds for every point
            // too (the clearance may be lower still, near unseen space).
            assert!(
                closest.max(0.0) >= result.occupied,
                "{context}: shape {i} occupied bound {} but point {at:?} is {closest} away",
                result.occupied
            );
            if closest <= 0.0 {
                assert_eq!(c, 0.0, "{context}: shape {i} contains {at:?}");
                assert!(
                    report.stop,
                    "{context}: shape {i} contains {at:?} but no stop"
                );
                tally.hits += 1;
            }
            // Non-trivial bounds: the occupied-space bound (near the domain's
            // border or a trimmed triangle the clearance itself is 0).
            tally.positive += usize::from(result.occupied > 0.0);
            tally.shapes += 1;
        }
        tally
    }

    fn demo_arm() -> ArmFile {
        ArmFile::from_toml_str(DEMO_ARM).expect("the demo arm file is valid")
    }

    /// Joint values within the limits; every other configuration reaches down
    /// (shoulder lift, elbow and wrist within ±0.7 rad), into the clouds.
    fn random_joints(arm: &ArmModel, rng: &mut Pcg64) -> Vec<f64> {
        let down = rng.random_bool(0.5);
        arm.actuated_joints()
            .enumerate()
            .map(|(i, j)| {
                let (lo, hi) = j.limits().map_or((-3.0, 3.0), |l| (l.lower, l.upper));
                let (lo, hi) = if down && (1..=3).contains(&i) {
                    (lo.max(-0.7), hi.min(0.7))
                } else {
                    (lo, hi)
                };
                rng.random_range(lo..=hi)
            })
            .collect()
    }

    fn spheres_scene(points: usize, seed: u64, time: f64) -> Vec<[f32; 3]> {
        shroud_sim::MovingSpheres {
            points,
            seed,
            ..Default::default()
        }
        .generate(time)
        .expect("default scene is valid")
    }

    #[test]
    fn demo_arm_file_describes_a_six_joint_fifty_sphere_arm() {
        let file = demo_arm();
        let arm = &file.arm;
        assert_eq!(
            (arm.dof(), arm.shape_count(), arm.links().len()),
            (6, 50, 7)
        );
        assert_eq!(file.guard, GuardConfig::default());
        let trajectory = file.trajectory.as_ref().expect("the demo has a trajectory");
        assert!(trajectory.looping() && trajectory.period() > 5.0);
        // The base hangs above the scene, and the trajectory stays within limits.
        let base = arm.base().translation;
        assert!((base - glam::DVec3::new(0.0, 0.0, 1.6)).length() < 1e-12);
        for i in 0..200 {
            let q = trajectory.positions_at(i as f64 * 0.07).unwrap();
            arm.check_limits(&q).unwrap();
            let pose = arm.forward(&q).unwrap();
            assert_eq!(pose.shapes.len(), 50);
        }
        // Straight down the fingertips reach z = 0.23 (1.35 m below the mount, minus their radius).
        let pose = arm.forward(&[0.0; 6]).unwrap();
        let lowest = pose
            .shapes
            .iter()
            .map(|s| match s.shape {
                Shape::Sphere(s) => s.centre.z - s.radius,
                Shape::Capsule(c) => c.a.z.min(c.b.z) - c.radius,
            })
            .fold(f64::INFINITY, f64::min);
        assert!((lowest - 0.23).abs() < 1e-9, "{lowest}");
    }

    #[test]
    fn small_arm_parses_and_moves() {
        let arm = ArmModel::from_toml_str(SMALL_ARM).unwrap();
        assert_eq!((arm.dof(), arm.shape_count()), (2, 6));
        let pose = arm.forward(&[0.5, 0.0]).unwrap();
        // Lifted by 0.5 along the flipped z: the slider starts at z = 1.5.
        assert!((pose.links[1].translation - DVec3::new(0.0, 0.0, 1.5)).length() < 1e-12);
        assert!((pose.links[3].translation - DVec3::new(0.0, 0.0, 0.2)).length() < 1e-12);
        assert!(arm.forward(&[0.5]).is_err());
    }

    /// Both poses of the bench: far (folded up) is clear, near (hanging into the
    /// larger sphere) stops.
    #[test]
    fn bench_poses_far_is_clear_and_near_stops() {
        let points = spheres_scene(30_000, 0, 0.3);
        let sur = fit(&points, Sides::Sandwich, [0.0, 0.0, -1.0], 20).unwrap();
        let env = Envelope::new(&sur).unwrap();
        let file = demo_arm();
        let cfg = file.guard;
        let far = file.arm.forward(&[0.0, 1.2, 2.2, 1.0, 0.0, 0.0]).unwrap();
        let near = file.arm.forward(&[0.6, 0.3, 0.5, 0.4, 0.5, 0.3]).unwrap();
        let far_report = check_arm(&env, &far, &cfg).unwrap();
        let near_report = check_arm(&env, &near, &cfg).unwrap();
        let pts = points_f64(&points);
        assert_conservative(&far.shapes, &far_report, &pts, "far");
        assert_conservative(&near.shapes, &near_report, &pts, "near");
        assert!(!far_report.stop, "far pose: {:?}", far_report.min_clearance);
        assert!(far_report.min_clearance > 0.1);
        assert!(near_report.stop);
        assert_eq!(near_report.links.len(), 7);
        assert!(near_report.closest_link.is_some_and(|l| l >= 2));
    }

    /// On a sandwich the guard is tight enough to be useful: where the brute-force
    /// distance is large, the bound is not much smaller.
    #[test]
    fn sandwich_bound_is_reasonably_tight_above_the_clouds() {
        let points = spheres_scene(30_000, 1, 0.3);
        let pts = points_f64(&points);
        let sur = fit(&points, Sides::Sandwich, [0.0, 0.0, -1.0], 20).unwrap();
        let env = Envelope::new(&sur).unwrap();
        let cfg = GuardConfig {
            stop_distance: 0.3,
            max_report: 1.0,
            refine_depth: 4,
            max_obstacle_speed: 0.0,
            horizon: 0.0,
        };
        let mut rng = Pcg64::seed_from_u64(9);
        let mut ratios = Vec::new();
        for _ in 0..200 {
            let c = DVec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(1.3..1.8),
            );
            let shape = Shape::sphere(c, 0.05);
            let truth = pts
                .iter()
                .map(|p| shape.distance_to(*p))
                .fold(f64::INFINITY, f64::min);
            let bound = env.shape_clearance(&shape, &cfg).unwrap();
            assert!(bound <= truth.max(0.0));
            if truth < 0.9 && truth > 0.1 {
                ratios.push(bound / truth);
            }
        }
        ratios.sort_by(f64::total_cmp);
        let median = ratios[ratios.len() / 2];
        assert!(median > 0.6, "median bound/true distance {median}");
    }

    /// Spheres centred exactly on cloud points, radii down to 1e-9: all touch.
    #[test]
    fn tiny_spheres_on_cloud_points_always_stop() {
        for (kind, sides) in [
            (CloudKind::SimSpheres, Sides::Sandwich),
            (CloudKind::Cliff, Sides::Upper),
            (CloudKind::Spikes, Sides::Lower),
            (CloudKind::Holes, Sides::Sandwich),
            (CloudKind::Lattice, Sides::Sandwich),
        ] {
            let c = cloud(kind, 5000, 3);
            let Some(sur) = fit(&c.points, sides, [0.0, 0.0, -1.0], 12) else {
                continue;
            };
            let env = Envelope::new(&sur).unwrap();
            let cfg = GuardConfig {
                stop_distance: 0.0,
                ..GuardConfig::default()
            };
            for (i, p) in points_f64(&c.points).iter().enumerate().step_by(37) {
                for r in [1e-9, 1e-6, 1e-3] {
                    let shape = WorldShape {
                        link: 0,
                        shape: Shape::sphere(*p, r),
                    };
                    let report = check_shapes(&env, &[shape], 1, &cfg).unwrap();
                    assert!(
                        report.stop && report.min_clearance == 0.0,
                        "{kind:?} point {i} radius {r}: {report:?}"
                    );
                }
            }
        }
    }

    /// The hole in the middle of the annulus cloud is trimmed: a sphere there sees
    /// the ring (at 0.7) and not a surface spanning the hole as occupied, and
    /// the hole itself as space the view did not see.
    #[test]
    fn spheres_inside_a_trimmed_hole_see_only_the_ring() {
        let c = cloud(CloudKind::Holes, 20_000, 5);
        let sur = fit(&c.points, Sides::Sandwich, [0.0, 0.0, -1.0], 40).unwrap();
        let env = Envelope::new(&sur).unwrap();
        let pts = points_f64(&c.points);
        let cfg = GuardConfig {
            stop_distance: 0.05,
            max_report: 1.0,
            refine_depth: 4,
            max_obstacle_speed: 0.0,
            horizon: 0.0,
        };
        let mut positive = 0;
        let mut rng = Pcg64::seed_from_u64(1);
        let mut shapes = Vec::new();
        for _ in 0..100 {
            let (a, r): (f64, f64) = (
                rng.random_range(0.0..std::f64::consts::TAU),
                rng.random_range(0.0..0.3),
            );
            shapes.push(WorldShape {
                link: 0,
                shape: Shape::sphere(
                    DVec3::new(r * a.cos(), r * a.sin(), rng.random_range(-0.3..0.3)),
                    0.05,
                ),
            });
        }
        let report = check_shapes(&env, &shapes, 1, &cfg).unwrap();
        assert_conservative(&shapes, &report, &pts, "hole");
        for s in &report.shapes {
            positive += usize::from(s.occupied > 0.0);
            assert!(
                s.unobserved && s.unseen == 0.0 && s.clearance == 0.0,
                "{s:?}"
            );
        }
        assert!(
            positive > 80,
            "only {positive} of 100 spheres in the hole are clear of the ring"
        );
    }

    /// Every supported side: sandwiches, and one-sided surrogates whose occupied
    /// region is a half-space over the domain.
    #[test]
    fn one_sided_surrogates_guard_the_half_space() {
        let points = spheres_scene(10_000, 4, 1.0);
        let pts = points_f64(&points);
        let file = demo_arm();
        let mut rng = Pcg64::seed_from_u64(4);
        for sides in [Sides::Upper, Sides::Lower, Sides::Sandwich] {
            let sur = fit(&points, sides, [0.0, 0.0, -1.0], 16).unwrap();
            let env = Envelope::new(&sur).unwrap();
            for _ in 0..10 {
                let pose = file
                    .arm
                    .forward(&random_joints(&file.arm, &mut rng))
                    .unwrap();
                let report = check_arm(&env, &pose, &file.guard).unwrap();
                assert_conservative(&pose.shapes, &report, &in_domain(&sur, &pts), "sides");
            }
            // Far below the clouds a lone upper surface says occupied.
            let deep = Shape::sphere(DVec3::new(0.0, 0.0, -50.0), 0.1);
            let c = env.shape_clearance(&deep, &file.guard).unwrap();
            match sides {
                Sides::Upper => assert_eq!(c, 0.0),
                _ => assert_eq!(c, file.guard.max_report),
            }
        }
    }

    /// Shapes of random kinds near a cloud, scaled to its size.
    fn random_shapes(
        sur: &Surrogate,
        pts: &[DVec3],
        count: usize,
        rng: &mut Pcg64,
    ) -> (Vec<WorldShape>, f64) {
        let d = &sur.domain;
        let (eu, ev) = (
            d.u_step * (d.cols - 1) as f64,
            d.v_step * (d.rows - 1) as f64,
        );
        let size = eu.max(ev);
        let frame = &sur.frame;
        let mut shapes = Vec::with_capacity(count);
        for i in 0..count {
            let radius = size * 10f64.powf(rng.random_range(-7.0..-0.7));
            let anchor = pts[rng.random_range(0..pts.len())];
            let jitter = DVec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            ) * radius
                * rng.random_range(0.0..3.0);
            let centre = match i % 4 {
                // Near a cloud point.
                0 | 1 => anchor + jitter,
                // On the domain's border (u or v at its extreme), at a point's height.
                2 => {
                    let l = frame.to_local(anchor);
                    let (u, v) = if rng.random_bool(0.5) {
                        (d.u_min + if rng.random_bool(0.5) { 0.0 } else { eu }, l.y)
                    } else {
                        (l.x, d.v_min + if rng.random_bool(0.5) { 0.0 } else { ev })
                    };
                    frame.to_world(DVec3::new(u, v, l.z)) + jitter
                }
                // Anywhere around the domain.
                _ => {
                    let l = frame.to_local(anchor);
                    frame.to_world(DVec3::new(
                        d.u_min + rng.random_range(-0.2..1.2) * eu,
                        d.v_min + rng.random_range(-0.2..1.2) * ev,
                        l.z + rng.random_range(-0.3..0.3) * size,
                    ))
                }
            };
            let shape = if rng.random_bool(0.25) {
                let other = pts[rng.random_range(0..pts.len())];
                Shape::capsule(
                    centre,
                    centre + (other - centre) * rng.random_range(0.0..1.0),
                    radius,
                )
            } else {
                Shape::sphere(centre, radius)
            };
            shapes.push(WorldShape { link: 0, shape });
        }
        (shapes, size)
    }

    const ADVERSARIAL: [CloudKind; 15] = [
        CloudKind::Huge,
        CloudKind::Tiny,
        CloudKind::TiltedPlane,
        CloudKind::ExtremeHeights,
        CloudKind::Spikes,
        CloudKind::Cliff,
        CloudKind::Holes,
        CloudKind::TightClusters,
        CloudKind::Pillar,
        CloudKind::Lattice,
        CloudKind::UniformBox,
        CloudKind::Duplicates,
        CloudKind::FarOffset,
        CloudKind::SimTerrain,
        CloudKind::SimSpheres,
    ];

    proptest! {
        #![proptest_config(config(40))]

        /// Random configurations of the demo arm over the moving spheres, any side,
        /// any grid: brute force over every point.
        #[test]
        fn demo_arm_random_configurations_are_conservative(
            seed in any::<u64>(),
            time in 0.0f64..13.0,
            sides in select(vec![Sides::Sandwich, Sides::Upper, Sides::Lower]),
            grid in 4usize..30,
            depth in 0u32..5,
        ) {
            let points = spheres_scene(15_000, seed, time);
            let pts = points_f64(&points);
            let Some(sur) = fit(&points, sides, [0.0, 0.0, -1.0], grid) else {
                return Ok(());
            };
            let env = Envelope::new(&sur).unwrap();
            let file = demo_arm();
            let cfg = GuardConfig { refine_depth: depth, ..file.guard };
            let mut rng = Pcg64::seed_from_u64(seed);
            let pts = in_domain(&sur, &pts);
            for k in 0..6 {
                let pose = file.arm.forward(&random_joints(&file.arm, &mut rng)).unwrap();
                let report = check_arm(&env, &pose, &cfg).unwrap();
                assert_conservative(&pose.shapes, &report, &pts, &format!("pose {k}"));
            }
        }

        /// Random spheres and capsules (radii from 1e-7 to 0.2 of the cloud's size)
        /// over adversarial clouds, any direction and side.
        #[test]
        fn random_shapes_over_adversarial_clouds_are_conservative(
            kind in select(ADVERSARIAL.to_vec()),
            seed in any::<u64>(),
            sides in select(vec![Sides::Sandwich, Sides::Upper, Sides::Lower]),
            grid in 3usize..25,
            axis_aligned in any::<bool>(),
            depth in 0u32..5,
        ) {
            let c = cloud(kind, 4000, seed);
            let dir_kind = if axis_aligned { DirectionKind::Axis } else { DirectionKind::Random };
            let dir = if kind == CloudKind::Spikes || kind == CloudKind::Cliff {
                [0.0, 0.0, -1.0]
            } else {
                direction(dir_kind, c.normal, seed)
            };
            let Some(sur) = fit(&c.points, sides, dir, grid) else {
                return Ok(());
            };
            let env = Envelope::new(&sur).unwrap();
            let pts = in_domain(&sur, &points_f64(&c.points));
            let mut rng = Pcg64::seed_from_u64(seed ^ 0x5EED);
            let (shapes, size) = random_shapes(&sur, &pts, 60, &mut rng);
            let cfg = GuardConfig { stop_distance: 0.02 * size, max_report: 0.3 * size, refine_depth: depth, max_obstacle_speed: 0.0, horizon: 0.0 };
            let report = check_shapes(&env, &shapes, 1, &cfg).unwrap();
            assert_conservative(&shapes, &report, &pts, &format!("{kind:?}"));
        }

        /// The small arm (prismatic, revolute, fixed joints, capsules) over terrain.
        #[test]
        fn small_arm_over_terrain_is_conservative(
            seed in any::<u64>(),
            lift in 0.0f64..1.0,
            swing in -1.5f64..1.5,
            sides in select(vec![Sides::Sandwich, Sides::Upper]),
        ) {
            let c = cloud(CloudKind::SimTerrain, 8000, seed);
            let Some(sur) = fit(&c.points, sides, [0.0, 0.0, -1.0], 16) else {
                return Ok(());
            };
            let env = Envelope::new(&sur).unwrap();
            let pts = points_f64(&c.points);
            let arm = ArmModel::from_toml_str(SMALL_ARM).unwrap();
            // Place the arm over a random cloud point, low enough to touch sometimes.
            let mut rng = Pcg64::seed_from_u64(seed);
            let target = pts[rng.random_range(0..pts.len())];
            let pose = arm.forward(&[lift, swing]).unwrap();
            let shift = DVec3::new(target.x, target.y, target.z - 0.8 + rng.random_range(-0.5..0.5));
            let shapes: Vec<WorldShape> = pose
                .shapes
                .iter()
                .map(|s| WorldShape {
                    link: s.link,
                    shape: s.shape.transformed(&glam::DAffine3::from_translation(shift)),
                })
                .collect();
            let report = check_shapes(&env, &shapes, pose.link_count(), &GuardConfig::default()).unwrap();
            assert_conservative(&shapes, &report, &pts, "small arm");
        }
    }

    /// Enough of the random shapes really collide for the properties above to mean
    /// something (a deterministic sample of the same generators).
    #[test]
    fn the_random_shapes_do_hit_the_clouds() {
        let mut total = Tally::default();
        for (i, kind) in ADVERSARIAL.iter().enumerate() {
            let c = cloud(*kind, 4000, i as u64);
            let Some(sur) = fit(&c.points, Sides::Sandwich, [0.0, 0.0, -1.0], 12) else {
                continue;
            };
            let env = Envelope::new(&sur).unwrap();
            let pts = points_f64(&c.points);
            let mut rng = Pcg64::seed_from_u64(i as u64);
            let (shapes, size) = random_shapes(&sur, &pts, 100, &mut rng);
            let cfg = GuardConfig {
                stop_distance: 0.02 * size,
                max_report: 0.3 * size,
                refine_depth: 3,
                max_obstacle_speed: 0.0,
                horizon: 0.0,
            };
            let report = check_shapes(&env, &shapes, 1, &cfg).unwrap();
            let t = assert_conservative(&shapes, &report, &pts, &format!("{kind:?}"));
            total.hits += t.hits;
            total.shapes += t.shapes;
            total.positive += t.positive;
        }
        assert!(total.hits * 10 > total.shapes, "{total:?}");
        assert!(total.positive * 5 > total.shapes, "{total:?}");
    }

    /// The random arm configurations really reach into the clouds (a deterministic
    /// sample of the same generator): many shapes contain points, many are clear.
    #[test]
    fn the_random_arm_configurations_do_hit_the_clouds() {
        let file = demo_arm();
        let mut total = Tally::default();
        let mut stops = 0;
        for seed in 0..6u64 {
            let points = spheres_scene(15_000, seed, seed as f64 * 2.1);
            let pts = points_f64(&points);
            let sur = fit(&points, Sides::Sandwich, [0.0, 0.0, -1.0], 20).unwrap();
            let env = Envelope::new(&sur).unwrap();
            let mut rng = Pcg64::seed_from_u64(seed);
            for _ in 0..10 {
                let pose = file
                    .arm
                    .forward(&random_joints(&file.arm, &mut rng))
                    .unwrap();
                let report = check_arm(&env, &pose, &file.guard).unwrap();
                let t = assert_conservative(&pose.shapes, &report, &pts, "tally");
                stops += usize::from(report.stop);
                total.hits += t.hits;
                total.shapes += t.shapes;
                total.positive += t.positive;
            }
        }
        eprintln!("{total:?}, {stops} of 60 poses stop");
        assert!(total.hits * 20 > total.shapes, "{total:?}");
        assert!(total.positive * 2 > total.shapes, "{total:?}");
        assert!((10..55).contains(&stops), "{stops} of 60 poses stop");
    }

    /// Largest speed of a Lissajous path: `|d/dt a sin(w t + p)| <= a w` per axis.
    fn speed_bound(path: &shroud_sim::LissajousPath) -> f64 {
        path.amplitude
            .iter()
            .zip(&path.angular_speed)
            .map(|(a, w)| (a * w).powi(2))
            .sum::<f64>()
            .sqrt()
    }

    /// The cloud taken at `t0`, each point carried along with its sphere to
    /// `t1`: the scene as it is when the guard decides (the simulator knows it).
    fn moved_cloud(
        scene: &shroud_sim::MovingSpheres,
        points: &[[f32; 3]],
        t0: f64,
        t1: f64,
    ) -> Vec<DVec3> {
        let (c0, c1) = (scene.centres(t0), scene.centres(t1));
        let first = scene.counts()[0];
        points
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let k = usize::from(i >= first);
                let shift = DVec3::from_array(c1[k]) - DVec3::from_array(c0[k]);
                DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64) + shift
            })
            .collect()
    }

    /// The whole decision over one to three views of the moving spheres, taken
    /// at `t0` and 50 and 100 ms before it, and judged at `t1` with the
    /// scene's true speed bound: every
    /// combined clearance is at most the shape's distance to the scene at
    /// `t1`, and a `clear` never hides a shape within the stop distance of it.
    /// Counted, so that the test cannot pass by never clearing.
    #[test]
    fn views_and_motion_allowance_are_never_optimistic() {
        use shroud_guard::{CollisionGuard, GuardPolicy, SurrogateInput, UnobservedPolicy};
        use shroud_msg::GuardVerdict;
        let file = demo_arm();
        let directions = [[0.0, 0.0, -1.0], [0.0, -1.0, 0.0], [-1.0, 0.0, 0.0]];
        let (mut clears, mut stops, mut hits, mut unobserved) = (0, 0, 0, 0);
        for seed in 0..6u64 {
            let scene = shroud_sim::MovingSpheres {
                points: 15_000,
                seed,
                ..Default::default()
            };
            let speed = scene.paths.iter().map(speed_bound).fold(0.0, f64::max);
            let t0 = seed as f64 * 1.7;
            let points = scene.generate(t0).unwrap();
            // View k sees the same points 50k ms earlier (carried back along
            // their spheres' paths): views of one scene at different ages.
            let views: Vec<SurrogateInput> = directions
                .iter()
                .enumerate()
                .map(|(k, &d)| {
                    let earlier = t0 - 0.05 * k as f64;
                    let seen: Vec<[f32; 3]> = moved_cloud(&scene, &points, t0, earlier)
                        .iter()
                        .map(|p| p.as_vec3().to_array())
                        .collect();
                    let surrogate = fit(&seen, Sides::Sandwich, d, 16).unwrap();
                    SurrogateInput {
                        envelope: Envelope::new(&surrogate).unwrap(),
                        stamp_ns: 0,
                        sequence: seed,
                        pipeline_ns: 20_000_000 + 50_000_000 * k as u64,
                        published_ns: 0,
                        position_error: 0.0,
                    }
                })
                .collect();
            let mut rng = Pcg64::seed_from_u64(seed);
            for count in 1..=3 {
                let age_s = rng.random_range(0.0..0.12);
                let truth = moved_cloud(&scene, &points, t0, t0 + 0.02 + age_s);
                let config = GuardConfig {
                    max_report: 0.6,
                    max_obstacle_speed: speed,
                    ..file.guard
                };
                // Every point of the cloud lies in every view's domain, so the
                // bounds hold for every shape; unobserved space is about what
                // the cloud does not hold, which this scene has none of.
                let policy = GuardPolicy {
                    max_skew_ns: u64::MAX,
                    unobserved: UnobservedPolicy::Ignore,
                    ..GuardPolicy::default()
                };
                let names = (0..count).map(|i| format!("v{i}")).collect();
                let links = file.arm.links().iter().map(|l| l.name.clone()).collect();
                let mut guard = CollisionGuard::new(names, links, policy, config).unwrap();
                for (v, input) in views.iter().take(count).enumerate() {
                    guard.accept(v, input.clone(), 0, 0).unwrap();
                }
                for k in 0..20 {
                    // Half anywhere (mostly into the clouds), half near the
                    // folded-up pose above them (mostly clear).
                    let q: Vec<f64> = if k % 2 == 0 {
                        random_joints(&file.arm, &mut rng)
                    } else {
                        [0.0, 1.2, 2.2, 1.0, 0.0, 0.0]
                            .iter()
                            .map(|q| q + rng.random_range(-0.3..0.3))
                            .collect()
                    };
                    let pose = file.arm.forward(&q).unwrap();
                    let d = guard.decide(&pose.shapes, (age_s * 1e9) as u64).unwrap();
                    let report = d.report.as_ref().unwrap();
                    for (shape, result) in pose.shapes.iter().zip(&report.shapes) {
                        let closest = truth
                            .iter()
                            .map(|p| shape.shape.distance_to(*p))
                            .fold(f64::INFINITY, f64::min);
                        hits += usize::from(closest <= 0.0);
                        assert!(
                            result.clearance <= closest.max(0.0),
                            "{count} views: clearance {} but the scene is {closest} away",
                            result.clearance
                        );
                        if d.verdict == GuardVerdict::Clear {
                            assert!(
                                closest >= config.stop_distance,
                                "clear with a shape {closest} m from the scene"
                            );
                        }
                    }
                    clears += usize::from(d.verdict == GuardVerdict::Clear);
                    stops += usize::from(d.verdict == GuardVerdict::Stop);
                    unobserved += usize::from(d.verdict == GuardVerdict::Unobserved);
                }
            }
        }
        eprintln!("{clears} clear, {stops} stop, {unobserved} unobserved, {hits} shapes inside the moved scene");
        assert!(
            clears >= 30 && stops >= 50 && hits >= 100,
            "{clears} clear, {stops} stop, {hits} hits"
        );
    }
}
