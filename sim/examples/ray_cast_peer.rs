//! Times the range scanner's hand-written BVH ([`Bvh`]) against parry3d's
//! `TriMesh` (with its own BVH) on the scanner's meshes and rays, and checks
//! that both find the same first hits. Run with
//!
//! ```text
//! cargo run --release -p shroud-sim --example ray_cast_peer --features parry-compare
//! ```
//!
//! Per mesh it prints the build time of each acceleration structure, and per
//! (mesh, ray count) the time to cast one scan frame of rays on one thread and
//! on rayon's pool (as `RangeScanner::scan` does, a row per task): medians of
//! `REPEATS` runs, and the median ratio parry / shroud of back-to-back runs
//! (above 1: shroud is faster). Both return the distance and the normal of the
//! first hit, which is what the scanner needs (range and intensity); parry by
//! its fastest path to that answer, and for reference by
//! `cast_local_ray_and_get_normal`. parry's build time includes narrowing the
//! f64 mesh to its f32 vertices, as `Bvh::build` does. Rays whose first hits
//! differ are printed to stderr with an f64 brute-force answer.

use parry3d::math::Vector;
use parry3d::query::{Ray, RayCast};
use parry3d::shape::{CompositeShapeRef, TriMesh};
use rayon::prelude::*;
use shroud_shapes::format::TriangleMesh;
use shroud_sim::{
    Bvh, RangeScanner, ScanResolution, TableTop, Terrain, DEFAULT_CYLINDER_SEGMENTS,
    DEFAULT_TERRAIN_CELLS,
};
use std::hint::black_box;
use std::ops::Range;
use std::time::{Duration, Instant};

/// Runs per timing; the median is reported.
const REPEATS: usize = 11;
/// Scan time of the frame whose rays are cast (the scanners orbit).
const TIME: f64 = 1.0;
/// Ray counts of one frame: the scanner's default and ten times that.
const RAY_COUNTS: [usize; 2] = [30_000, 300_000];
/// Largest relative difference of two hit distances counted as equal.
const TOLERANCE: f32 = 1e-4;

/// The first hit of a ray: distance and unit normal.
type Hit = Option<(f32, [f32; 3])>;

/// One scan frame's rays, as `RangeScanner::scan` casts them.
struct Frame {
    origin: [f32; 3],
    directions: Vec<[f32; 3]>,
    /// The rays of each row, as index ranges into `directions`.
    rows: Vec<Range<usize>>,
    max_distance: f32,
}

/// The rays of `scanner`'s frame at `time`: the same grid, angles and f32
/// rounding as `RangeScanner::scan` (checked against it by `check_rays`).
fn frame(scanner: &RangeScanner, time: f64) -> Frame {
    let sensor = scanner.pose.sensor(time).expect("the scanner has a pose");
    let (rays, rows) = (scanner.rays(), scanner.grid()[1]);
    let rays_before = |row: usize| (row as u128 * rays as u128 / rows as u128) as usize;
    let angle =
        |fov: f64, n: usize, i: usize| (fov * ((i as f64 + 0.5) / n as f64 - 0.5)).sin_cos();
    let mut directions = Vec::with_capacity(rays);
    let mut ranges = Vec::with_capacity(rows);
    for row in 0..rows {
        let (se, ce) = angle(scanner.vertical_fov, rows, rows - 1 - row);
        let columns = rays_before(row + 1) - rays_before(row);
        let start = directions.len();
        for column in 0..columns {
            let (sa, ca) = angle(scanner.horizontal_fov, columns, column);
            let d: [f64; 3] = std::array::from_fn(|k| {
                ce * (ca * sensor.forward[k] + sa * sensor.right[k]) + se * sensor.up[k]
            });
            directions.push(d.map(|c| c as f32));
        }
        ranges.push(start..directions.len());
    }
    Frame {
        origin: sensor.position.map(|c| c as f32),
        directions,
        rows: ranges,
        max_distance: scanner.max_range as f32,
    }
}

/// Checks that `frame` holds the scanner's rays: without noise and dropouts
/// the scan's points are exactly where shroud's hits along these rays are.
fn check_rays(scanner: &RangeScanner, bvh: &Bvh, frame: &Frame, hits: &[Hit]) {
    let exact = RangeScanner {
        range_noise: 0.0,
        dropout: 0.0,
        ..scanner.clone()
    };
    let scan = exact.scan(bvh, TIME).expect("scan");
    let origin = frame.origin.map(f64::from);
    let points: Vec<[f32; 3]> = frame
        .directions
        .iter()
        .zip(hits)
        .filter_map(|(d, hit)| {
            let range = f64::from(hit.as_ref()?.0);
            Some(std::array::from_fn(|k| {
                (origin[k] + f64::from(d[k]) * range) as f32
            }))
        })
        .collect();
    assert_eq!(scan.rays, frame.directions.len());
    assert!(scan.points == points, "the rays differ from the scanner's");
}

fn cast_shroud(bvh: &Bvh, frame: &Frame, rays: Range<usize>) -> Vec<Hit> {
    frame.directions[rays]
        .iter()
        .map(|&d| {
            bvh.intersect(frame.origin, d, frame.max_distance)
                .map(|h| (h.distance, h.normal))
        })
        .collect()
}

/// parry's fastest way to the scanner's answer: `TriMesh`'s distance-only
/// traversal (`CompositeShapeRef::cast_local_ray`, which also names the hit
/// triangle), then that triangle's normal.
fn cast_parry(mesh: &TriMesh, frame: &Frame, rays: Range<usize>) -> Vec<Hit> {
    let origin = Vector::from_array(frame.origin);
    let composite = CompositeShapeRef(mesh);
    frame.directions[rays]
        .iter()
        .map(|&d| {
            let ray = Ray::new(origin, Vector::from_array(d));
            let (triangle, distance) = composite.cast_local_ray(&ray, frame.max_distance, false)?;
            let normal = mesh.triangle(triangle).normal().unwrap_or(Vector::ZERO);
            Some((distance, normal.to_array()))
        })
        .collect()
}

/// parry's `RayCast::cast_local_ray_and_get_normal` (another traversal), for
/// comparison.
fn cast_parry_with_normal(mesh: &TriMesh, frame: &Frame, rays: Range<usize>) -> Vec<Hit> {
    let origin = Vector::from_array(frame.origin);
    frame.directions[rays]
        .iter()
        .map(|&d| {
            let ray = Ray::new(origin, Vector::from_array(d));
            mesh.cast_local_ray_and_get_normal(&ray, frame.max_distance, false)
                .map(|h| (h.time_of_impact, h.normal.to_array()))
        })
        .collect()
}

/// Casts every ray of `frame` on one thread.
fn single(frame: &Frame, cast: impl Fn(Range<usize>) -> Vec<Hit>) -> Vec<Hit> {
    cast(0..frame.directions.len())
}

/// Casts `frame` on rayon's pool, a row per task, as the scanner does.
fn parallel(frame: &Frame, cast: impl Fn(Range<usize>) -> Vec<Hit> + Sync) -> Vec<Hit> {
    let rows: Vec<Vec<Hit>> = frame.rows.par_iter().map(|r| cast(r.clone())).collect();
    rows.concat()
}

fn build_parry(mesh: &TriangleMesh) -> TriMesh {
    let vertices = mesh
        .vertices
        .iter()
        .map(|v| Vector::from_array(v.map(|c| c as f32)))
        .collect();
    TriMesh::new(vertices, mesh.triangles.clone()).expect("parry builds the mesh")
}

fn median(mut times: Vec<Duration>) -> Duration {
    times.sort();
    let n = times.len();
    (times[(n - 1) / 2] + times[n / 2]) / 2
}

/// The median time of `REPEATS` runs of `f`, and its last result.
fn timed<T>(mut f: impl FnMut() -> T) -> (Duration, T) {
    let mut times = Vec::with_capacity(REPEATS);
    let mut last = None;
    for _ in 0..REPEATS {
        let start = Instant::now();
        let out = black_box(f());
        times.push(start.elapsed());
        last = Some(out);
    }
    (median(times), last.expect("REPEATS > 0"))
}

/// Median times of shroud's and parry's runs, and the median of the ratios
/// parry / shroud of runs made back to back (alternating which goes first),
/// so that other load on the machine weighs on both alike.
struct Timing {
    shroud: Duration,
    parry: Duration,
    ratio: f64,
}

/// Times `shroud` and `parry` `REPEATS` times each, interleaved; returns the
/// timing and their last results.
fn paired<A, B>(mut shroud: impl FnMut() -> A, mut parry: impl FnMut() -> B) -> (Timing, A, B) {
    let (mut a_times, mut b_times, mut ratios) = (Vec::new(), Vec::new(), Vec::new());
    let (mut a, mut b) = (None, None);
    for k in 0..REPEATS {
        let mut run_a = || {
            let start = Instant::now();
            a = Some(black_box(shroud()));
            start.elapsed()
        };
        let mut run_b = || {
            let start = Instant::now();
            b = Some(black_box(parry()));
            start.elapsed()
        };
        let (ta, tb) = if k % 2 == 0 {
            let ta = run_a();
            (ta, run_b())
        } else {
            let tb = run_b();
            (run_a(), tb)
        };
        ratios.push(tb.as_secs_f64() / ta.as_secs_f64());
        a_times.push(ta);
        b_times.push(tb);
    }
    ratios.sort_by(f64::total_cmp);
    let timing = Timing {
        shroud: median(a_times),
        parry: median(b_times),
        ratio: (ratios[(REPEATS - 1) / 2] + ratios[REPEATS / 2]) / 2.0,
    };
    (timing, a.expect("REPEATS > 0"), b.expect("REPEATS > 0"))
}

/// The nearest hit of ray `ray` of `frame` with `mesh` (its vertices narrowed
/// to f32, as both casters store them) in f64, by brute force, as `(distance,
/// margin)`: `margin` is the smallest barycentric coordinate of
/// the hit point (0 on an edge), relative to the triangle. Only hits whose
/// margin is at least `-slack` count.
fn reference(mesh: &TriangleMesh, frame: &Frame, ray: usize, slack: f64) -> Option<(f64, f64)> {
    let o = frame.origin.map(f64::from);
    let d = frame.directions[ray].map(f64::from);
    let sub = |a: [f64; 3], b: [f64; 3]| -> [f64; 3] { std::array::from_fn(|k| a[k] - b[k]) };
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let mut best: Option<(f64, f64)> = None;
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| mesh.vertices[i as usize].map(|c| f64::from(c as f32)));
        let (e1, e2) = (sub(b, a), sub(c, a));
        let p = cross(d, e2);
        let det = dot(e1, p);
        if det == 0.0 {
            continue;
        }
        let s = sub(o, a);
        let u = dot(s, p) / det;
        let q = cross(s, e1);
        let v = dot(d, q) / det;
        let margin = u.min(v).min(1.0 - u - v);
        let t = dot(e2, q) / det;
        if margin >= -slack
            && t > 0.0
            && t < f64::from(frame.max_distance)
            && best.is_none_or(|(b, _)| t < b)
        {
            best = Some((t, margin));
        }
    }
    best
}

/// Hit/miss disagreements and distances differing by more than `TOLERANCE`
/// (relative), printing the first few with the f64 brute-force answer.
fn mismatches(
    case: &str,
    mesh: &TriangleMesh,
    frame: &Frame,
    shroud: &[Hit],
    parry: &[Hit],
) -> usize {
    let mut count = 0;
    for (i, (a, b)) in shroud.iter().zip(parry).enumerate() {
        let same = match (a, b) {
            (None, None) => true,
            (Some(a), Some(b)) => (a.0 - b.0).abs() <= TOLERANCE * a.0.max(b.0),
            _ => false,
        };
        if !same {
            if count < 8 {
                let exact = reference(mesh, frame, i, 0.0);
                let slack = reference(mesh, frame, i, 1e-5);
                eprintln!(
                    "{case}: ray {i}: shroud {:?}, parry {:?}, f64 brute force {exact:?} \
                     (with 1e-5 barycentric slack {slack:?})",
                    a.map(|h| h.0),
                    b.map(|h| h.0)
                );
            }
            count += 1;
        }
    }
    count
}

/// A closed, bumpy sphere of radius about 1 (a scanned part), `rings` x
/// `2 * rings` cells: about `4 * rings^2` triangles, counter-clockwise outwards.
fn bumpy_sphere(rings: u32) -> TriangleMesh {
    use std::f64::consts::PI;
    let sectors = 2 * rings;
    let mut mesh = TriangleMesh::default();
    let radius = |theta: f64, phi: f64| 1.0 + 0.05 * (7.0 * theta).sin() * (5.0 * phi).cos();
    mesh.vertices.push([0.0, 0.0, radius(0.0, 0.0)]);
    for i in 1..rings {
        let theta = PI * f64::from(i) / f64::from(rings);
        for j in 0..sectors {
            let phi = 2.0 * PI * f64::from(j) / f64::from(sectors);
            let r = radius(theta, phi);
            mesh.vertices.push([
                r * theta.sin() * phi.cos(),
                r * theta.sin() * phi.sin(),
                r * theta.cos(),
            ]);
        }
    }
    let south = mesh.vertices.len() as u32;
    mesh.vertices.push([0.0, 0.0, -radius(PI, 0.0)]);
    let at = |i: u32, j: u32| 1 + (i - 1) * sectors + j % sectors;
    for j in 0..sectors {
        mesh.triangles.push([0, at(1, j), at(1, j + 1)]);
        mesh.triangles
            .push([south, at(rings - 1, j + 1), at(rings - 1, j)]);
    }
    for i in 1..rings - 1 {
        for j in 0..sectors {
            let [a, b, c, d] = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
            mesh.triangles.push([a, b, c]);
            mesh.triangles.push([a, c, d]);
        }
    }
    mesh
}

fn ms(d: Duration) -> String {
    format!("{:.2}", d.as_secs_f64() * 1e3)
}

fn row(t: &Timing) -> String {
    format!("{} | {} | {:.2}", ms(t.shroud), ms(t.parry), t.ratio)
}

fn main() {
    let terrain = RangeScanner::default();
    let part = bumpy_sphere(256);
    let cases = [
        (
            "scan-table-top",
            TableTop::default()
                .mesh(DEFAULT_CYLINDER_SEGMENTS)
                .expect("table mesh"),
            RangeScanner::default(),
        ),
        (
            "scan-terrain",
            Terrain::default()
                .mesh(DEFAULT_TERRAIN_CELLS)
                .expect("terrain mesh"),
            terrain.clone(),
        ),
        (
            "scan-terrain 400x300",
            Terrain::default().mesh([400, 300]).expect("terrain mesh"),
            terrain,
        ),
        (
            "scan-mesh (bumpy sphere)",
            part.clone(),
            RangeScanner::orbiting(&part).expect("orbit"),
        ),
    ];
    println!(
        "{} threads in rayon's pool; medians of {REPEATS} runs; ratio = median of parry / shroud over back-to-back runs",
        rayon::current_num_threads()
    );
    println!();
    println!("| mesh | triangles | build shroud (ms) | build parry (ms) | ratio |");
    println!("|---|---:|---:|---:|---:|");
    let mut structures = Vec::new();
    for (name, mesh, scanner) in &cases {
        let (build, bvh, trimesh) = paired(|| Bvh::build(mesh).expect("BVH"), || build_parry(mesh));
        println!("| {name} | {} | {} |", mesh.triangles.len(), row(&build));
        structures.push((name, mesh, scanner, bvh, trimesh));
    }
    println!();
    println!(
        "| mesh | rays | hits | 1 thread shroud (ms) | parry (ms) | ratio \
         | parry, cast_local_ray_and_get_normal (ms) | pool shroud (ms) | parry (ms) | ratio | mismatches |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let mut total_mismatches = 0;
    for (name, mesh, scanner, bvh, trimesh) in &structures {
        for rays in RAY_COUNTS {
            let scanner = RangeScanner {
                resolution: ScanResolution::Points(rays),
                ..(*scanner).clone()
            };
            let frame = frame(&scanner, TIME);
            let shroud = |r| cast_shroud(bvh, &frame, r);
            let parry = |r| cast_parry(trimesh, &frame, r);
            let (one, shroud_hits, parry_hits) =
                paired(|| single(&frame, shroud), || single(&frame, parry));
            let (parry_normal, parry_normal_hits) =
                timed(|| cast_parry_with_normal(trimesh, &frame, 0..frame.directions.len()));
            let (pool, shroud_pool_hits, parry_pool_hits) =
                paired(|| parallel(&frame, shroud), || parallel(&frame, parry));
            assert!(shroud_pool_hits == shroud_hits && parry_pool_hits == parry_hits);
            check_rays(&scanner, bvh, &frame, &shroud_hits);
            let case = format!("{name}, {rays} rays");
            let wrong = mismatches(&case, mesh, &frame, &shroud_hits, &parry_hits);
            let distances = |hits: &[Hit]| hits.iter().map(|h| h.map(|h| h.0)).collect::<Vec<_>>();
            if distances(&parry_normal_hits) != distances(&parry_hits) {
                eprintln!("{case}: parry's two traversals differ");
            }
            total_mismatches += wrong;
            println!(
                "| {name} | {rays} | {} | {} | {} | {} | {wrong} |",
                shroud_hits.iter().flatten().count(),
                row(&one),
                ms(parry_normal),
                row(&pool),
            );
        }
    }
    println!();
    println!("{total_mismatches} rays where the first hits differ (hit/miss, or distance by > {TOLERANCE} relative)");
}
