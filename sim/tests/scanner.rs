//! The range scanner against analytic cases (planes and boxes at known places),
//! its noise and dropout statistics, determinism, every invalid configuration,
//! and meshes read back from files. `scan_timing` (ignored) measures it:
//! `cargo test --release -p shroud-sim --test scanner -- --ignored --nocapture`.

use shroud_shapes::format::{parse_triangle_mesh, TriangleMesh};
use shroud_sim::{
    Bvh, LissajousPath, RangeScanner, ScanPose, ScanResolution, Scene, SceneError, TableBox,
    TableTop, TableTopScan, TerrainScan,
};
use std::time::Instant;

/// A square of half-width `half` in the plane z = `z`, facing up.
fn square(half: f64, z: f64) -> TriangleMesh {
    TriangleMesh {
        vertices: vec![
            [-half, -half, z],
            [half, -half, z],
            [half, half, z],
            [-half, half, z],
        ],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
    }
}

/// A noise-free scanner at `position` looking at `target` with a grid of rays.
fn exact_scanner(
    position: [f64; 3],
    target: [f64; 3],
    fov: [f64; 2],
    grid: [usize; 2],
) -> RangeScanner {
    RangeScanner {
        pose: ScanPose::fixed(position, target),
        horizontal_fov: fov[0].to_radians(),
        vertical_fov: fov[1].to_radians(),
        resolution: ScanResolution::Grid {
            columns: grid[0],
            rows: grid[1],
        },
        max_range: 100.0,
        range_noise: 0.0,
        dropout: 0.0,
        seed: 0,
    }
}

fn distance(a: [f32; 3], b: [f64; 3]) -> f64 {
    (0..3)
        .map(|k| (f64::from(a[k]) - b[k]).powi(2))
        .sum::<f64>()
        .sqrt()
}

#[test]
fn plane_at_known_distance_gives_exact_ranges() {
    let bvh = Bvh::build(&square(100.0, 0.0)).unwrap();
    let [columns, rows] = [41, 31];
    let scanner = exact_scanner([0.0, 0.0, 10.0], [0.0; 3], [60.0, 40.0], [columns, rows]);
    let frame = scanner.scan(&bvh, 0.0).unwrap();
    assert_eq!(
        (frame.points.len(), frame.rays),
        (columns * rows, columns * rows)
    );
    // Looking down: right is +x, up is +y; the top row comes first.
    let (h, v) = (scanner.horizontal_fov, scanner.vertical_fov);
    for (i, (p, intensity)) in frame.points.iter().zip(&frame.intensity).enumerate() {
        let (row, column) = (i / columns, i % columns);
        let azimuth = h * ((column as f64 + 0.5) / columns as f64 - 0.5);
        let elevation = v * ((rows - 1 - row) as f64 + 0.5) / rows as f64 - 0.5 * v;
        let expected = [
            10.0 * azimuth.tan(),
            10.0 * elevation.tan() / azimuth.cos(),
            0.0,
        ];
        assert!(distance(*p, expected) < 2e-5, "{i}: {p:?} vs {expected:?}");
        assert!(p[2].abs() < 2e-6, "{p:?}");
        let range = distance(*p, [0.0, 0.0, 10.0]);
        let exact = 10.0 / (azimuth.cos() * elevation.cos());
        assert!((range - exact).abs() < 2e-5, "{range} vs {exact}");
        assert!((f64::from(*intensity) - azimuth.cos() * elevation.cos()).abs() < 1e-5);
    }
    assert_eq!(frame.sensor.position, [0.0, 0.0, 10.0]);
}

#[test]
fn oblique_plane_hits_lie_on_it_and_max_range_cuts() {
    // A plane through (0, 0, 1) with normal (1, 0, 1)/√2, seen from the side.
    let mut mesh = square(50.0, 0.0);
    for v in &mut mesh.vertices {
        v[2] = 1.0 - v[0];
    }
    let bvh = Bvh::build(&mesh).unwrap();
    let scanner = exact_scanner([8.0, 1.0, 9.0], [0.0, 0.0, 1.0], [50.0, 30.0], [30, 20]);
    let frame = scanner.scan(&bvh, 0.0).unwrap();
    assert_eq!(frame.points.len(), 600);
    for p in &frame.points {
        assert!(
            (f64::from(p[0]) + f64::from(p[2]) - 1.0).abs() < 2e-5,
            "{p:?}"
        );
    }
    let nearest = frame
        .points
        .iter()
        .map(|p| distance(*p, [8.0, 1.0, 9.0]))
        .fold(f64::INFINITY, f64::min);
    let short = RangeScanner {
        max_range: nearest - 1e-3,
        ..scanner.clone()
    };
    assert!(short.scan(&bvh, 0.0).unwrap().points.is_empty());
    let farthest = frame
        .points
        .iter()
        .map(|p| distance(*p, [8.0, 1.0, 9.0]))
        .fold(0.0, f64::max);
    let mid = RangeScanner {
        max_range: 0.5 * (nearest + farthest),
        ..scanner
    };
    let cut = mid.scan(&bvh, 0.0).unwrap().points;
    assert!(!cut.is_empty() && cut.len() < 600);
    assert!(cut
        .iter()
        .all(|p| distance(*p, [8.0, 1.0, 9.0]) <= mid.max_range + 1e-4));
}

fn one_box_table() -> TableTop {
    TableTop {
        boxes: vec![TableBox {
            min: [-1.0, -1.0],
            max: [1.0, 1.0],
            height: 0.5,
        }],
        cylinders: vec![],
        ..TableTop::default()
    }
}

#[test]
fn a_box_seen_from_above_gives_its_top() {
    let table = one_box_table();
    // Narrow enough for every ray to land on the 2 x 2 top from 4.5 above it.
    let narrow = exact_scanner([0.0, 0.0, 5.0], [0.0; 3], [20.0, 20.0], [25, 25]);
    let scan = TableTopScan::new(table.clone(), narrow.clone());
    let frame = scan.scan(0.0).unwrap();
    assert_eq!(frame.points.len(), 625);
    for p in &frame.points {
        assert!((p[2] - 0.5).abs() < 1e-6, "{p:?}");
        assert!(p[0].abs() < 1.0 && p[1].abs() < 1.0);
    }
    // The corner rays meet the top 14° off its normal.
    assert!(frame.intensity.iter().all(|&i| i > 0.96));
    // Wider: the top inside the footprint, the table outside it, nothing else
    // (the walls face away from a scanner above the centre).
    let wide = RangeScanner {
        horizontal_fov: 60f64.to_radians(),
        vertical_fov: 50f64.to_radians(),
        resolution: ScanResolution::Grid {
            columns: 120,
            rows: 100,
        },
        ..narrow
    };
    let points = TableTopScan::new(table, wide).scan(0.0).unwrap().points;
    assert_eq!(points.len(), 12_000);
    let (mut top, mut floor) = (0, 0);
    for p in &points {
        let inside = p[0].abs() <= 1.0 + 1e-5 && p[1].abs() <= 1.0 + 1e-5;
        if (p[2] - 0.5).abs() < 1e-6 && inside {
            top += 1;
        } else if p[2].abs() < 1e-6 && !(p[0].abs() < 1.0 && p[1].abs() < 1.0) {
            floor += 1;
        } else {
            panic!("{p:?} is neither on the top nor on the table");
        }
    }
    assert!(top > 1_000 && floor > 5_000, "{top} {floor}");
}

#[test]
fn a_box_seen_from_the_side_shows_its_wall_and_occludes() {
    let table = one_box_table();
    // Level with the box's middle, looking along +x at its -x wall.
    let scanner = exact_scanner([-6.0, 0.0, 0.25], [0.0, 0.0, 0.25], [10.0, 4.0], [20, 8]);
    let points = TableTopScan::new(table, scanner).scan(0.0).unwrap().points;
    assert_eq!(points.len(), 160);
    for p in &points {
        assert!((p[0] + 1.0).abs() < 1e-5, "{p:?} is not on the near wall");
        assert!((0.0..=0.5).contains(&p[2]) && p[1].abs() <= 1.0);
    }
}

fn plane_scanner(noise: f64, dropout: f64, seed: u64) -> RangeScanner {
    RangeScanner {
        range_noise: noise,
        dropout,
        seed,
        ..exact_scanner([0.0, 0.0, 10.0], [0.0; 3], [40.0, 40.0], [200, 200])
    }
}

#[test]
fn dropout_rate_matches_its_probability() {
    let bvh = Bvh::build(&square(100.0, 0.0)).unwrap();
    for dropout in [0.0, 0.05, 0.25, 0.6] {
        let frame = plane_scanner(0.0, dropout, 3).scan(&bvh, 1.0).unwrap();
        let kept = frame.points.len() as f64 / frame.rays as f64;
        // Four standard deviations of a binomial proportion over 40 000 rays.
        let tolerance = 4.0 * (dropout * (1.0 - dropout) / 40_000.0).sqrt() + 1e-12;
        assert!(
            (kept - (1.0 - dropout)).abs() <= tolerance,
            "{dropout}: kept {kept}"
        );
    }
}

#[test]
fn range_noise_is_gaussian_with_the_given_sigma() {
    let bvh = Bvh::build(&square(100.0, 0.0)).unwrap();
    let sigma = 0.02;
    let frame = plane_scanner(sigma, 0.0, 8).scan(&bvh, 0.0).unwrap();
    let origin = [0.0, 0.0, 10.0];
    // Range error: measured range minus the true range to z = 0 along the ray.
    let errors: Vec<f64> = frame
        .points
        .iter()
        .map(|p| {
            let range = distance(*p, origin);
            let cos = (10.0 - f64::from(p[2])) / range;
            range - 10.0 / cos
        })
        .collect();
    let n = errors.len() as f64;
    let mean = errors.iter().sum::<f64>() / n;
    let std = (errors.iter().map(|e| (e - mean).powi(2)).sum::<f64>() / n).sqrt();
    assert!(mean.abs() < 4.0 * sigma / n.sqrt(), "mean {mean}");
    assert!((std / sigma - 1.0).abs() < 0.03, "std {std}");
    let beyond = errors.iter().filter(|e| e.abs() > 2.0 * sigma).count() as f64 / n;
    assert!((beyond - 0.0455).abs() < 0.006, "{beyond} beyond 2 sigma");
}

#[test]
fn scans_are_deterministic_per_seed_and_time_whatever_the_threads() {
    let scene = Scene::by_name("scan-table-top", 20_000, 4).unwrap();
    let a = scene.generate(0.7).unwrap();
    assert_eq!(a, scene.generate(0.7).unwrap());
    assert_eq!(a, scene.generate(-0.0 + 0.7).unwrap());
    let single = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    assert_eq!(a, single.install(|| scene.generate(0.7).unwrap()));
    let triple = rayon::ThreadPoolBuilder::new()
        .num_threads(3)
        .build()
        .unwrap();
    assert_eq!(a, triple.install(|| scene.generate(0.7).unwrap()));
    let other_seed = Scene::by_name("scan-table-top", 20_000, 5).unwrap();
    assert_ne!(a, other_seed.generate(0.7).unwrap());
    // The orbit moves the scanner: consecutive frames (30 Hz) differ.
    assert_ne!(a, scene.generate(0.7 + 1.0 / 30.0).unwrap());
    assert_eq!(
        Scene::by_name("scan-terrain", 5_000, 1)
            .unwrap()
            .generate(2.0)
            .unwrap(),
        Scene::by_name("scan-terrain", 5_000, 1)
            .unwrap()
            .generate(2.0)
            .unwrap()
    );
    // Without noise or dropouts a fixed scanner is static, and the seed is moot.
    let still = RangeScanner {
        pose: ScanPose::fixed([6.0, -5.0, 6.0], [0.0; 3]),
        range_noise: 0.0,
        dropout: 0.0,
        ..RangeScanner::default()
    };
    let scene = Scene::ScanTableTop(TableTopScan::new(TableTop::default(), still.clone()));
    assert!(!scene.is_animated());
    assert_eq!(scene.generate(0.0).unwrap(), scene.generate(9.0).unwrap());
    let reseeded = Scene::ScanTableTop(TableTopScan::new(
        TableTop::default(),
        RangeScanner { seed: 99, ..still },
    ));
    assert_eq!(
        scene.generate(0.0).unwrap(),
        reseeded.generate(0.0).unwrap()
    );
}

/// Whether `p` lies on the table-top geometry: on the top-most surface, or on a
/// box wall or (polygonal) cylinder wall between the table and the object's top.
fn on_table_geometry(table: &TableTop, p: [f32; 3], tolerance: f64) -> bool {
    let [x, y, z] = p.map(f64::from);
    if (z - table.height(x, y)).abs() <= tolerance {
        return true;
    }
    let on_box = table.boxes.iter().any(|b| {
        let within = |v: f64, lo: f64, hi: f64| v >= lo - tolerance && v <= hi + tolerance;
        let near = |v: f64, edge: f64| (v - edge).abs() <= tolerance;
        within(x, b.min[0], b.max[0])
            && within(y, b.min[1], b.max[1])
            && (near(x, b.min[0]) || near(x, b.max[0]) || near(y, b.min[1]) || near(y, b.max[1]))
            && within(z, 0.0, b.height)
    });
    // 48 segments: the flat sides lie up to r (1 - cos(pi / 48)) inside the rim.
    let on_cylinder = table.cylinders.iter().any(|c| {
        let r = (x - c.centre[0]).hypot(y - c.centre[1]);
        let sag = c.radius * (1.0 - (std::f64::consts::PI / 48.0).cos());
        r <= c.radius + tolerance
            && r >= c.radius - sag - tolerance
            && z >= -tolerance
            && z <= c.height + tolerance
    });
    on_box || on_cylinder
}

#[test]
fn the_default_table_top_scan_lies_on_the_table() {
    let mut scan = TableTopScan::default();
    scan.scanner.range_noise = 0.0;
    scan.scanner.dropout = 0.0;
    for time in [0.0, 1.3, 4.0] {
        let frame = scan.scan(time).unwrap();
        let hit_ratio = frame.points.len() as f64 / frame.rays as f64;
        assert!(hit_ratio > 0.6, "only {hit_ratio} of the rays hit");
        let off: Vec<_> = frame
            .points
            .iter()
            .filter(|p| !on_table_geometry(&scan.table, **p, 2e-4))
            .collect();
        // Points on the polygonal cylinder's top near its rim are outside the
        // true disc: TableTop::height says table there.
        assert!(
            off.len() * 1000 < frame.points.len(),
            "{} off, e.g. {:?}",
            off.len(),
            off.first()
        );
        let raised = frame.points.iter().filter(|p| p[2] > 0.01).count();
        assert!(raised > frame.points.len() / 20, "objects are seen");
    }
}

#[test]
fn the_default_terrain_scan_follows_the_height_field() {
    let mut scan = TerrainScan::default();
    scan.scanner.range_noise = 0.0;
    let frame = scan.scan(0.5).unwrap();
    assert!(frame.points.len() as f64 > 0.6 * frame.rays as f64);
    // Off the cells a cliff crosses (whose steep faces are seen too), the points
    // lie on the height field up to the mesh's interpolation error.
    let near_cliff = |x: f64, y: f64| {
        scan.terrain.cliffs.iter().any(|c| {
            let [nx, ny] = c.normal;
            let side = ((x - c.through[0]) * nx + (y - c.through[1]) * ny) / nx.hypot(ny);
            side.abs() < 0.08
        })
    };
    let mut on_faces = 0;
    for p in &frame.points {
        let [x, y, z] = p.map(f64::from);
        if near_cliff(x, y) {
            on_faces += 1;
        } else {
            let error = (z - scan.terrain.height(x, y)).abs();
            assert!(error < 2e-3, "{p:?} is {error} off the height field");
        }
    }
    assert!(
        on_faces > 0 && on_faces * 5 < frame.points.len(),
        "{on_faces}"
    );
    let (lo, hi) = (scan.terrain.min, scan.terrain.max);
    assert!(frame.points.iter().all(|p| {
        (lo[0]..=hi[0]).contains(&f64::from(p[0])) && (lo[1]..=hi[1]).contains(&f64::from(p[1]))
    }));
}

#[test]
fn meshes_read_from_obj_and_ply_scan_like_the_scene() {
    let scanner = RangeScanner {
        resolution: ScanResolution::Points(8_000),
        ..RangeScanner::default()
    };
    let table = TableTopScan::new(TableTop::default(), scanner.clone());
    let expected = table.scan(0.4).unwrap();
    let mesh = table.mesh().unwrap();
    // OBJ keeps f64 exactly and PLY stores f32, which the BVH uses anyway.
    for bytes in [mesh.to_obj(), mesh.to_ply(true), mesh.to_ply(false)] {
        let read = parse_triangle_mesh(&bytes).unwrap();
        let scene = Scene::scan_mesh(read, scanner.clone()).unwrap();
        assert_eq!(scene.scan_frame(0.4).unwrap().unwrap(), expected);
    }
    // Framed whole: the table is seen, and every point is on it (up to the
    // 5 mm range noise).
    let framed = RangeScanner::orbiting(&mesh).unwrap();
    let scene = Scene::scan_mesh(mesh, framed).unwrap();
    for time in [0.0, 2.0, 4.0] {
        let points = scene.generate(time).unwrap();
        assert!(
            points.len() > scene.points() / 6,
            "{} of {}",
            points.len(),
            scene.points()
        );
        assert!(points
            .iter()
            .all(|p| p[0].abs() <= 4.05 && p[1].abs() <= 3.05 && p[2] > -0.05 && p[2] < 1.45));
    }
}

/// Asserts that `result` failed naming `parameter`.
fn assert_names(result: Result<impl std::fmt::Debug, SceneError>, parameter: &str) {
    let err = result.expect_err(parameter);
    assert!(err.to_string().contains(parameter), "{parameter}: {err}");
}

#[test]
fn every_invalid_configuration_is_an_error_naming_it() {
    let bvh = Bvh::build(&square(10.0, 0.0)).unwrap();
    let good = plane_scanner(0.01, 0.1, 0);
    assert!(good.scan(&bvh, 0.0).is_ok());
    let with = |change: &dyn Fn(&mut RangeScanner)| {
        let mut scanner = good.clone();
        change(&mut scanner);
        scanner.scan(&bvh, 0.0)
    };
    let fov = |value: f64, which: usize| {
        with(&|s: &mut RangeScanner| {
            if which == 0 {
                s.horizontal_fov = value;
            } else {
                s.vertical_fov = value;
            }
        })
    };
    for value in [0.0, -0.5, std::f64::consts::PI, 4.0] {
        let err = fov(value, 0).unwrap_err();
        assert!(matches!(err, SceneError::OutOfInterval { .. }), "{err}");
        assert!(err.to_string().contains("horizontal_fov") && err.to_string().contains("(0, π)"));
        assert_names(fov(value, 1), "vertical_fov");
    }
    assert_names(fov(f64::NAN, 0), "horizontal_fov");
    assert_names(fov(f64::INFINITY, 1), "vertical_fov");
    let grid = |columns, rows| {
        with(&move |s: &mut RangeScanner| s.resolution = ScanResolution::Grid { columns, rows })
    };
    assert!(matches!(grid(0, 5), Err(SceneError::ZeroResolution { .. })));
    assert_names(grid(0, 5), "resolution.columns");
    assert_names(grid(5, 0), "resolution.rows");
    assert!(matches!(
        grid(usize::MAX, 3),
        Err(SceneError::TooManyPoints { .. })
    ));
    assert_names(
        with(&|s: &mut RangeScanner| s.resolution = ScanResolution::Points(0)),
        "resolution.points",
    );
    assert_names(
        with(&|s: &mut RangeScanner| s.resolution = ScanResolution::Points(usize::MAX)),
        "resolution.points",
    );
    for value in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert_names(
            with(&|s: &mut RangeScanner| s.max_range = value),
            "max_range",
        );
    }
    for value in [-1e-9, f64::NAN, f64::INFINITY] {
        assert_names(
            with(&|s: &mut RangeScanner| s.range_noise = value),
            "range_noise",
        );
    }
    for value in [1.0, 1.5, -0.01, f64::NAN] {
        assert_names(with(&|s: &mut RangeScanner| s.dropout = value), "dropout");
    }
    let err = with(&|s: &mut RangeScanner| s.dropout = 1.0).unwrap_err();
    assert!(err.to_string().contains("[0, 1)"), "{err}");
    assert_names(
        with(&|s: &mut RangeScanner| s.pose.target[2] = f64::NAN),
        "pose.target[2]",
    );
    assert_names(
        with(&|s: &mut RangeScanner| s.pose.position.amplitude[0] = f64::INFINITY),
        "pose.position.amplitude[0]",
    );
    assert_names(
        with(&|s: &mut RangeScanner| s.pose = ScanPose::fixed([1.0, 2.0, 3.0], [1.0, 2.0, 3.0])),
        "pose",
    );
    // An orbit through its own target at one moment only.
    let mut through = good.clone();
    through.pose = ScanPose {
        position: LissajousPath {
            centre: [0.0, 0.0, 0.0],
            amplitude: [1.0, 0.0, 0.0],
            angular_speed: [1.0, 0.0, 0.0],
            phase: [0.0; 3],
        },
        target: [0.0; 3],
    };
    assert!(through.scan(&bvh, 1.0).is_ok());
    assert_names(through.scan(&bvh, 0.0), "pose");
    assert_names(good.scan(&bvh, f64::NAN), "time");

    // Scenes: their geometry and the mesh.
    let mut scan = TableTopScan::default();
    scan.segments = 2;
    assert_names(scan.scan(0.0), "segments");
    let mut scan = TableTopScan::default();
    scan.table.boxes[1].height = -1.0;
    assert_names(scan.scan(0.0), "boxes[1].height");
    let mut scan = TerrainScan::default();
    scan.cells = [0, 10];
    assert_names(scan.scan(0.0), "cells[0]");
    assert_names(scan.validate(), "cells[0]");
    let mut scan = TerrainScan::default();
    scan.terrain.hills[0].width = 0.0;
    assert_names(scan.validate(), "hills[0].width");
    let mut scan = TerrainScan::default();
    scan.scanner.dropout = 2.0;
    assert_names(Scene::ScanTerrain(scan).prepare(), "dropout");
    let bad_meshes = [
        (TriangleMesh::default(), "no vertices"),
        (
            TriangleMesh {
                triangles: vec![],
                ..square(1.0, 0.0)
            },
            "no triangles",
        ),
        (
            TriangleMesh {
                triangles: vec![[0, 1, 9]],
                ..square(1.0, 0.0)
            },
            "refers to vertex 9",
        ),
        (
            TriangleMesh {
                vertices: vec![[0.0, f64::NAN, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
                triangles: vec![[0, 1, 2]],
            },
            "vertex 0 coordinate 1 is NaN",
        ),
        (
            TriangleMesh {
                vertices: vec![[0.0; 3]; 3],
                triangles: vec![[0, 1, 2]],
            },
            "zero area",
        ),
    ];
    for (mesh, expected) in bad_meshes {
        assert_names(Scene::scan_mesh(mesh, RangeScanner::default()), expected);
    }
    assert_names(
        Scene::scan_mesh(square(1.0, 0.0), RangeScanner::default())
            .unwrap()
            .attach_mesh(TriangleMesh::default()),
        "no vertices",
    );
}

#[test]
fn scan_scenes_round_trip_through_json() {
    let scene = Scene::by_name("scan-terrain", 1_234, 9).unwrap();
    let json = serde_json::to_string(&scene).unwrap();
    assert!(json.contains(r#""kind":"scan-terrain""#), "{json}");
    let back: Scene = serde_json::from_str(&json).unwrap();
    assert_eq!(back, scene);
    assert_eq!(back.generate(0.3).unwrap(), scene.generate(0.3).unwrap());
    let minimal: Scene = serde_json::from_str(
        r#"{"kind": "scan-table-top", "scanner": {"resolution": {"points": 500}, "dropout": 0.5}}"#,
    )
    .unwrap();
    assert_eq!(minimal.points(), 500);
    let fixed: Scene = serde_json::from_str(
        r#"{"kind": "scan-terrain", "cells": [40, 30], "scanner": {
              "pose": {"position": {"centre": [0, -6, 8]}, "target": [0, 0, 0]},
              "range_noise": 0, "dropout": 0}}"#,
    )
    .unwrap();
    assert!(!fixed.is_animated());
    let sensor = fixed.scan_frame(0.0).unwrap().unwrap().sensor;
    assert_eq!(sensor.position, [0.0, -6.0, 8.0]);
    assert_eq!(fixed.generate(0.0).unwrap(), fixed.generate(5.0).unwrap());
    assert_eq!(minimal.scanner().unwrap().dropout, 0.5);
    assert!(!minimal.generate(0.0).unwrap().is_empty());
}

/// CPU time this thread has run, in ms (Linux `schedstat`), if available: on a
/// loaded machine it measures the work, where the wall clock measures the load.
fn thread_cpu_ms() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let nanos: f64 = text.split_whitespace().next()?.parse().ok()?;
    Some(nanos * 1e-6)
}

#[test]
#[ignore = "timing: run in release with --ignored --nocapture"]
fn scan_timing() {
    let threads = rayon::current_num_threads();
    println!("rayon threads: {threads}");
    let single = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    for (name, rays) in [
        ("scan-table-top", 30_000),
        ("scan-table-top", 300_000),
        ("scan-terrain", 30_000),
        ("scan-terrain", 300_000),
    ] {
        let start = Instant::now();
        let scene = Scene::by_name(name, rays, 0).unwrap();
        let build = start.elapsed();
        let mut wall = Vec::new();
        let mut points = 0;
        for frame in 0..21 {
            let start = Instant::now();
            points = scene.generate(f64::from(frame) / 30.0).unwrap().len();
            wall.push(start.elapsed().as_secs_f64() * 1e3);
        }
        wall.sort_by(f64::total_cmp);
        // One thread: its CPU time per scan, independent of other processes
        // (batches of scans, as the kernel's counter advances by scheduler ticks).
        let batch = 3_000_000 / rays;
        let mut cpu: Vec<f64> = (0..5)
            .filter_map(|round| {
                single.install(|| {
                    let before = thread_cpu_ms()?;
                    for frame in 0..batch {
                        let time = f64::from((round * batch + frame) as u32) / 30.0;
                        scene.generate(time).unwrap();
                    }
                    Some((thread_cpu_ms()? - before) / batch as f64)
                })
            })
            .collect();
        cpu.sort_by(f64::total_cmp);
        let cpu = cpu.get(cpu.len() / 2).copied().unwrap_or(f64::NAN);
        println!(
            "{name}: {} rays -> {points} points; {threads} threads wall median {:.2} ms (min {:.2}); \
             1 thread CPU median {cpu:.2} ms ({:.0} ns/ray); mesh + BVH {:.2} ms",
            scene.points(),
            wall[wall.len() / 2],
            wall[0],
            cpu * 1e6 / scene.points() as f64,
            build.as_secs_f64() * 1e3
        );
    }
}

/// Rays that miss the mesh are stated as cones from the optical centre (the
/// field of view's apex): beyond the edge of a square 10 m below, not over
/// its middle. Lone dropouts over a plane that fills the view state nothing.
#[test]
fn rays_without_return_are_stated_as_cones() {
    let bvh = Bvh::build(&square(3.0, 0.0)).unwrap();
    let scanner = exact_scanner([0.0, 0.0, 10.0], [0.0; 3], [60.0, 40.0], [121, 81]);
    let frame = scanner.scan(&bvh, 0.0).unwrap();
    let stated = frame
        .no_return
        .expect("rays beyond the square return nothing");
    let fov = scanner.field_of_view(0.0).unwrap();
    assert_eq!(stated.apex, fov.apex);
    assert!(stated.cones.len() <= shroud_msg::MAX_DARK_CONES);
    let covered = |p: [f64; 3]| {
        let d: [f64; 3] = std::array::from_fn(|k| p[k] - stated.apex[k]);
        let norm = d.iter().map(|x| x * x).sum::<f64>().sqrt();
        stated.cones.iter().any(|c| {
            let cos: f64 = (0..3).map(|k| c.axis[k] * d[k] / norm).sum();
            cos.clamp(-1.0, 1.0).acos() <= c.half_angle
        })
    };
    for beyond in [
        [3.2, 0.0, 0.0],
        [4.5, 0.0, 0.0],
        [0.0, -3.3, 0.0],
        [-4.0, 3.0, 0.0],
    ] {
        assert!(covered(beyond), "{beyond:?}");
    }
    for over in [[0.0, 0.0, 0.0], [1.5, 0.0, 0.0], [-1.0, 1.0, 0.5]] {
        assert!(!covered(over), "{over:?}");
    }
    let plane = Bvh::build(&square(100.0, 0.0)).unwrap();
    let noisy = RangeScanner {
        dropout: 0.01,
        ..scanner
    };
    let frame = noisy.scan(&plane, 0.0).unwrap();
    assert!(frame.points.len() < noisy.rays(), "some rays dropped out");
    assert_eq!(frame.no_return, None);
}

/// A grid whose neighbouring rays may be 1.55 rad or more apart (by the
/// azimuth plus the elevation step) could not state its empty rays as cones
/// under 90 degrees: it is refused when configured, by name, rather than
/// failing its scans. A single row (a planar scan) is not.
#[test]
fn a_grid_too_coarse_to_state_its_empty_rays_is_refused() {
    let coarse = exact_scanner([0.0, 0.0, 10.0], [0.0; 3], [150.0, 100.0], [2, 2]);
    let e = coarse.validate().unwrap_err().to_string();
    assert!(
        e.contains("resolution") && e.contains("neighbouring rays"),
        "{e}"
    );
    let planar = exact_scanner([0.0, 0.0, 10.0], [0.0; 3], [150.0, 100.0], [2, 1]);
    planar.validate().unwrap();
    let finer = exact_scanner([0.0, 0.0, 10.0], [0.0; 3], [150.0, 100.0], [3, 3]);
    finer.validate().unwrap();
}
