//! `shroud-bench peers` (issue 27, "Peers, side by side"): shroud's default
//! 20 x 20 upper surrogate against the peers a user would pick, on the same
//! clouds in one run: an elevation map (`shroud_surrogate::elevation`, per-cell
//! maxima) at equal storage and at the resolution that matches shroud's
//! tightness, and OctoMap with FCL (their Python bindings, in a venv the
//! benchmark makes under the target directory, `bench/peers/octomap_fcl.py`),
//! ray-cast from the sensor's origin and end points only, at 1, 2 and 5 cm.
//!
//! The scenes are solids of the guard's soundness harness (`shroud_sim::
//! soundness`), scanned from above by its perspective sensor with exact ray
//! casts, so that every test sphere is judged against exact geometry
//! (`soundness::truth::nearest`): the default table top's boxes
//! (`TableTop::default()`, scaled to a 2 x 1.5 m table, its cylinder as a box
//! of the same footprint area turned 30° to the grid: the soundness truth has
//! no cylinders) and the paper's two moving spheres (`MovingSpheres::
//! default()` at one time, halved, floating 0.25 m above the floor). Each at
//! 30K and 300K rays. The clouds and the test spheres go to the Python side
//! as `.npy` files; it echoes their counts and sums, which are checked.

use super::{median, timed, BenchArgs};
use anyhow::{bail, ensure, Context, Result};
use glam::{DQuat, DVec3};
use rand::{Rng, SeedableRng};
use shroud_guard::{check_shapes, Envelope, GuardConfig, Shape, WorldShape, MAX_REFINE_DEPTH};
use shroud_msg::SurrogateMessage;
use shroud_sim::soundness::truth::{nearest, Core};
use shroud_sim::soundness::{Body, FieldOfView, Sensor, Solid};
use shroud_sim::{MovingSpheres, TableTop};
use shroud_surrogate::elevation::ElevationMap;
use shroud_surrogate::{FitOptions, SurrogateFitter, SurrogateWire};
use std::hint::black_box;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Spheres per collision query, as the guard checks an arm.
const BATCH: usize = 50;
/// Test spheres per scene.
const SPHERES: usize = 2000;
/// Their radii (m).
const RADII: (f64, f64) = (0.02, 0.10);
/// The guard's stop distance in this benchmark (m): refinement needs one
/// above 0; a sphere whose true distance is within it counts as clear.
const STOP: f64 = 0.001;
/// OctoMap's resolutions (m).
const RESOLUTIONS: [f64; 3] = [0.01, 0.02, 0.05];
/// Elevation-map grids tried for the one that matches shroud's tightness
/// (coarser ones too: at equal storage the map is the tighter).
const GRIDS: [usize; 22] = [
    4, 5, 6, 7, 8, 10, 12, 14, 16, 18, 20, 24, 30, 36, 40, 50, 60, 80, 100, 120, 160, 240,
];
/// The Python packages, pinned (PyPI).
const PACKAGES: [&str; 3] = [
    "octomap-python==1.10.0.0",
    "python-fcl==0.7.0.11",
    "numpy==2.4.6",
];
const SCRIPT: &str = include_str!("../peers/octomap_fcl.py");

/// A scene of exact solids over the floor (z = 0), the box the test spheres
/// are drawn in, and where the sensor is.
struct Scene {
    name: &'static str,
    solids: Vec<Solid>,
    /// Test spheres' centres lie in `[lo, hi]` (x, y) and at most `top` high.
    lo: [f64; 2],
    hi: [f64; 2],
    top: f64,
    sensor_height: f64,
}

fn still(body: Body, centre: DVec3) -> Solid {
    Solid {
        body,
        centre,
        velocity: DVec3::ZERO,
        black: false,
    }
}

/// The default table top, a quarter of its size (a 2 x 1.5 m table).
fn table_top() -> Scene {
    let (table, s) = (TableTop::default(), 0.25);
    let mut solids: Vec<Solid> = table
        .boxes
        .iter()
        .map(|b| {
            let half = DVec3::new(b.max[0] - b.min[0], b.max[1] - b.min[1], b.height) * 0.5 * s;
            let centre = DVec3::new(b.min[0] + b.max[0], b.min[1] + b.max[1], b.height) * 0.5 * s;
            let rotation = DQuat::IDENTITY;
            still(Body::Cuboid { half, rotation }, centre)
        })
        .collect();
    solids.extend(table.cylinders.iter().map(|c| {
        let side = c.radius * std::f64::consts::PI.sqrt() * s;
        let half = DVec3::new(side, side, c.height * s) * 0.5;
        let rotation = DQuat::from_rotation_z(30f64.to_radians());
        let centre = DVec3::new(c.centre[0] * s, c.centre[1] * s, c.height * s * 0.5);
        still(Body::Cuboid { half, rotation }, centre)
    }));
    let top = solids.iter().map(|o| o.centre.z * 2.0).fold(0.0, f64::max) + 0.1;
    Scene {
        name: "table top",
        solids,
        lo: table.table_min.map(|x| x * s),
        hi: table.table_max.map(|x| x * s),
        top,
        sensor_height: 1.8,
    }
}

/// The paper's two spheres at t = 0.37 s, halved and floating.
fn moving_spheres() -> Scene {
    let (scene, s, time) = (MovingSpheres::default(), 0.5, 0.37);
    let balls: Vec<(DVec3, f64)> = scene
        .centres(time)
        .iter()
        .zip(scene.radii)
        .map(|(c, r)| (DVec3::from_array(*c) * s, f64::from(r) * s))
        .collect();
    let lowest = balls.iter().map(|(c, r)| c.z - r).fold(f64::MAX, f64::min);
    let lift = DVec3::Z * (0.25 - lowest);
    let solids: Vec<Solid> = balls
        .iter()
        .map(|&(c, radius)| still(Body::Sphere { radius }, c + lift))
        .collect();
    let (mut lo, mut hi, mut top) = ([f64::MAX; 2], [f64::MIN; 2], 0.0f64);
    for (o, &(_, r)) in solids.iter().zip(&balls) {
        for k in 0..2 {
            lo[k] = lo[k].min(o.centre[k] - r - 0.15);
            hi[k] = hi[k].max(o.centre[k] + r + 0.15);
        }
        top = top.max(o.centre.z + r + 0.1);
    }
    Scene {
        name: "moving spheres",
        solids,
        lo,
        hi,
        top,
        sensor_height: top + 1.5,
    }
}

impl Scene {
    /// The sensor above the middle of the sphere box, looking down, its
    /// frustum holding the box at the test spheres' top, with about `rays`
    /// rays (the floor fills every ray that misses the solids).
    fn sensor(&self, rays: usize) -> Sensor {
        let middle = [0, 1].map(|k| 0.5 * (self.lo[k] + self.hi[k]));
        let depth = self.sensor_height - self.top;
        let tan = [0, 1].map(|k| 0.5 * (self.hi[k] - self.lo[k]) / depth);
        let step = (4.0 * tan[0] * tan[1] / rays as f64).sqrt();
        let fov = FieldOfView::Frustum {
            half_x: tan[0].atan(),
            half_y: tan[1].atan(),
        };
        let origin = DVec3::new(middle[0], middle[1], self.sensor_height);
        Sensor::new(origin, DVec3::NEG_Z, fov, 10.0, step, 0.0)
    }

    /// `SPHERES` spheres in the box, each with whether it truly touches a
    /// solid or the floor (exact distance <= 0).
    fn spheres(&self, seed: u64) -> Vec<TestSphere> {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(seed);
        (0..SPHERES)
            .map(|_| {
                let r = rng.random_range(RADII.0..RADII.1);
                let c = DVec3::new(
                    rng.random_range(self.lo[0]..self.hi[0]),
                    rng.random_range(self.lo[1]..self.hi[1]),
                    rng.random_range(r..self.top),
                );
                let core = Core {
                    a: c,
                    b: c,
                    radius: r,
                };
                let distance = |radius| {
                    let core = Core { radius, ..core };
                    nearest(&core, &self.solids, 0.0, 0.0, f64::INFINITY).0
                };
                TestSphere {
                    centre: c.to_array(),
                    radius: r,
                    touching: distance(r) <= 0.0,
                    inside: distance(0.0) < 0.0,
                }
            })
            .collect()
    }
}

/// A test sphere and the truth about it.
#[derive(Debug, Clone, Copy)]
struct TestSphere {
    centre: [f64; 3],
    radius: f64,
    /// Its exact distance to a solid or the floor is <= 0.
    touching: bool,
    /// Its centre lies in a solid (space no sensor sees from outside).
    inside: bool,
}

/// One method's row on one cloud.
struct Row {
    method: String,
    build_ms: f64,
    runs: usize,
    bytes: usize,
    query_us: f64,
    blocked: Vec<bool>,
}

/// Unsafe (touching, called free), those of them with their centre inside
/// a solid, and conservative (clear, called blocked) counts.
fn score(blocked: &[bool], spheres: &[TestSphere]) -> (usize, usize, usize) {
    spheres
        .iter()
        .zip(blocked)
        .fold((0, 0, 0), |(u, i, c), (s, &b)| {
            let missed = s.touching && !b;
            (
                u + usize::from(missed),
                i + usize::from(missed && s.inside),
                c + usize::from(!s.touching && b),
            )
        })
}

/// Median time of each `BATCH` spheres' query (µs) and every sphere's answer.
fn queries(
    spheres: &[TestSphere],
    mut query: impl FnMut(&[TestSphere]) -> Result<Vec<bool>>,
) -> Result<(f64, Vec<bool>)> {
    let (mut times, mut blocked) = (vec![], vec![]);
    for chunk in spheres.chunks(BATCH) {
        let (answer, ms) = timed(|| query(chunk));
        if chunk.len() == BATCH {
            times.push(ms * 1e3);
        }
        blocked.extend(answer?);
    }
    Ok((median(&mut times), blocked))
}

/// shroud's default fit and the guard's envelope, queried with the guard's
/// default refinement depth and with `refine_depth`.
fn shroud_rows(
    points: &[[f32; 3]],
    spheres: &[TestSphere],
    runs: usize,
    refine_depth: u32,
) -> Result<Vec<Row>> {
    let mut times = vec![];
    let mut built = None;
    for _ in 0..runs {
        let mut fitter = SurrogateFitter::new(FitOptions::default())?;
        let (fit, ms) = timed(|| -> Result<_> {
            let surrogate = fitter.fit(points)?;
            let envelope = Envelope::new(&surrogate)?;
            Ok((surrogate, envelope))
        });
        times.push(ms);
        built = Some(fit?);
    }
    let (surrogate, envelope) = built.context("no run")?;
    for surface in surrogate.surfaces() {
        ensure!(surface.certificate.violations == 0, "uncertified surrogate");
    }
    let bytes = SurrogateMessage::from_surrogate(&surrogate, 0, 0, "", 0)
        .to_bytes()?
        .len();
    let build_ms = median(&mut times);
    let default = GuardConfig::default().refine_depth;
    let mut rows = vec![];
    for depth in [default, refine_depth] {
        let config = GuardConfig {
            stop_distance: STOP,
            refine_depth: depth,
            ..GuardConfig::default()
        };
        let (query_us, blocked) = queries(spheres, |chunk| {
            let shapes: Vec<WorldShape> = chunk
                .iter()
                .map(|s| WorldShape {
                    link: 0,
                    shape: Shape::sphere(DVec3::from_array(s.centre), s.radius),
                })
                .collect();
            let report = check_shapes(&envelope, &shapes, 1, &config)?;
            Ok(report
                .shapes
                .iter()
                .map(|s| s.clearance < STOP || s.clearance <= 0.0)
                .collect())
        })?;
        rows.push(Row {
            method: format!("shroud 20 x 20 (default fit + guard envelope, refine depth {depth})"),
            build_ms,
            runs,
            bytes,
            query_us,
            blocked,
        });
    }
    Ok(rows)
}

fn elevation_row(
    grid: usize,
    label: &str,
    points: &[[f32; 3]],
    spheres: &[TestSphere],
    runs: usize,
) -> Result<Row> {
    let mut map = ElevationMap::new(grid);
    let mut times = vec![];
    for _ in 0..runs {
        let ((), ms) = timed(|| map.build(black_box(points)));
        times.push(ms);
    }
    let (query_us, blocked) = queries(spheres, |chunk| {
        Ok(chunk
            .iter()
            .map(|s| map.sphere_blocked(s.centre, s.radius))
            .collect())
    })?;
    Ok(Row {
        method: format!("elevation map {grid} x {grid} ({label})"),
        build_ms: median(&mut times),
        runs,
        bytes: map.storage_bytes(),
        query_us,
        blocked,
    })
}

/// The coarsest grid of `GRIDS` whose conservative count is at most
/// `target` (shroud's on the same cloud; the finest grid when none is).
fn matching_grid(points: &[[f32; 3]], spheres: &[TestSphere], target: usize) -> usize {
    let conservative = |grid: usize| {
        let mut map = ElevationMap::new(grid);
        map.build(points);
        let blocked: Vec<bool> = spheres
            .iter()
            .map(|s| map.sphere_blocked(s.centre, s.radius))
            .collect();
        score(&blocked, spheres).2
    };
    GRIDS
        .into_iter()
        .find(|&grid| conservative(grid) <= target)
        .unwrap_or(GRIDS[GRIDS.len() - 1])
}

/// Little-endian `.npy` scalars.
pub(crate) trait NpyScalar: Copy {
    const DESCR: &'static str;
    fn put(self, out: &mut Vec<u8>);
}

impl NpyScalar for f32 {
    const DESCR: &'static str = "<f4";
    fn put(self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
}

impl NpyScalar for f64 {
    const DESCR: &'static str = "<f8";
    fn put(self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
}

/// An array as a `.npy` file (format 1.0, C order): `values` row by row,
/// `shape` its dimensions.
pub(crate) fn npy_bytes<T: NpyScalar>(shape: &[usize], values: &[T]) -> Vec<u8> {
    assert_eq!(shape.iter().product::<usize>(), values.len());
    let dims: String = shape.iter().map(|d| format!("{d}, ")).collect();
    let dims = if shape.len() == 1 {
        dims.trim_end().to_string()
    } else {
        dims.trim_end_matches(", ").to_string()
    };
    let mut header = format!(
        "{{'descr': '{}', 'fortran_order': False, 'shape': ({dims}), }}",
        T::DESCR
    );
    // Magic (6), version (2), length (2), header and newline: a multiple of 64.
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(' ');
    }
    header.push('\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    for v in values {
        v.put(&mut out);
    }
    out
}

/// Runs `command`, failing with its standard error unless it succeeds.
fn output_of(command: &mut Command, what: &str) -> Result<Vec<u8>> {
    let out = command
        .output()
        .with_context(|| format!("running {what}"))?;
    let stderr = String::from_utf8_lossy(&out.stderr);
    ensure!(out.status.success(), "{what} failed: {}", stderr.trim());
    Ok(out.stdout)
}

/// The interpreter of the venv `peers-venv` under the target directory,
/// made when missing, with `PACKAGES` installed from PyPI (pip leaves
/// pinned packages already there alone), as the tests' venvs are made.
fn python(target: &Path) -> Result<PathBuf> {
    let venv = target.join("peers-venv");
    let py = venv.join("bin/python3");
    if !py.exists() {
        let mut create = Command::new("python3");
        output_of(create.args(["-m", "venv"]).arg(&venv), "python3 -m venv")?;
    }
    let mut pip = Command::new(&py);
    pip.args([
        "-m",
        "pip",
        "install",
        "--quiet",
        "--disable-pip-version-check",
    ]);
    output_of(pip.args(PACKAGES), &format!("pip install {PACKAGES:?}"))?;
    Ok(py)
}

/// OctoMap + FCL on one cloud: writes the exchange files, runs the script,
/// checks that it read what was written, and returns its rows.
fn octomap_rows(
    py: &Path,
    dir: &Path,
    points: &[[f32; 3]],
    origin: DVec3,
    spheres: &[TestSphere],
    args: &BenchArgs,
) -> Result<(Vec<Row>, String)> {
    std::fs::create_dir_all(dir)?;
    let flat: Vec<f32> = points.iter().flatten().copied().collect();
    let balls: Vec<f64> = spheres
        .iter()
        .flat_map(|s| [s.centre[0], s.centre[1], s.centre[2], s.radius])
        .collect();
    std::fs::write(dir.join("points.npy"), npy_bytes(&[points.len(), 3], &flat))?;
    std::fs::write(dir.join("origin.npy"), npy_bytes(&[3], &origin.to_array()))?;
    std::fs::write(
        dir.join("spheres.npy"),
        npy_bytes(&[spheres.len(), 4], &balls),
    )?;
    let script = dir.join("octomap_fcl.py");
    std::fs::File::create(&script)?.write_all(SCRIPT.as_bytes())?;
    let resolutions: Vec<String> = RESOLUTIONS.iter().map(f64::to_string).collect();
    let (max_runs, budget) = if args.quick { ("1", "0") } else { ("5", "10") };
    let mut script_run = Command::new(py);
    script_run
        .arg(&script)
        .arg(dir)
        .args(["--resolutions", &resolutions.join(",")])
        .args(["--batch", &BATCH.to_string()])
        .args(["--max-runs", max_runs, "--budget", budget]);
    let stdout = output_of(&mut script_run, "octomap_fcl.py")?;
    let json: serde_json::Value = serde_json::from_slice(&stdout)?;
    // The round trip of the exchange files: counts exact, sums to rounding.
    let read = &json["read"];
    let sum = |v: &[f64]| v.iter().sum::<f64>();
    let point_sum = sum(&flat.iter().map(|&x| f64::from(x)).collect::<Vec<_>>());
    let close = |a: f64, b: &serde_json::Value| {
        b.as_f64()
            .is_some_and(|b| (a - b).abs() <= 1e-9 * (1.0 + a.abs()))
    };
    ensure!(
        read["points"].as_u64() == Some(points.len() as u64)
            && read["spheres"].as_u64() == Some(spheres.len() as u64)
            && close(point_sum, &read["point_sum"])
            && close(sum(&balls), &read["sphere_sum"]),
        "octomap_fcl.py read other clouds than written: {read}"
    );
    let versions = format!(
        "{}, {}",
        json["octomap"].as_str().unwrap_or("?"),
        json["fcl"].as_str().unwrap_or("?"),
    );
    let mut rows = vec![];
    for r in json["results"].as_array().context("no results")? {
        let mode = match r["mode"].as_str() {
            Some("rays") => "rays from the origin",
            _ => "end points only",
        };
        let blocked: Vec<bool> = r["blocked"]
            .as_str()
            .context("no answers")?
            .bytes()
            .map(|b| b == b'1')
            .collect();
        ensure!(blocked.len() == spheres.len(), "answers missing");
        rows.push(Row {
            method: format!(
                "OctoMap {} cm, {mode} + FCL (to FCL: {:.0} ms)",
                r["resolution"].as_f64().unwrap_or(f64::NAN) * 100.0,
                r["fcl_convert_ms"].as_f64().unwrap_or(f64::NAN)
            ),
            build_ms: r["build_ms"].as_f64().unwrap_or(f64::NAN),
            runs: r["build_runs"].as_u64().unwrap_or(0) as usize,
            bytes: r["memory_bytes"].as_u64().unwrap_or(0) as usize,
            query_us: r["query_ms"].as_f64().unwrap_or(f64::NAN) * 1e3,
            blocked,
        });
    }
    Ok((rows, versions))
}

pub fn run(args: &BenchArgs) -> Result<()> {
    let runs = if args.quick {
        3
    } else {
        args.runs.clamp(1, 20)
    };
    let sizes: &[usize] = if args.quick {
        &[30_000]
    } else {
        &[30_000, 300_000]
    };
    let threads = rayon::current_num_threads();
    println!(
        "# shroud-bench peers (shroud: {threads} rayon threads; elevation map, OctoMap (its wheel is \
         built without OpenMP) and FCL: 1 thread)\n"
    );
    println!(
        "{SPHERES} test spheres per scene, radii {}-{} m, the same for every method and both clouds; \
         a 50-sphere query is one `check_shapes` call (shroud), 50 `sphere_blocked` calls (elevation \
         map), 50 `fcl.collide` calls from Python (OctoMap). Unsafe: truly touching (exact distance <= 0), \
         called free; conservative: truly clear, called blocked. shroud's stop distance {} m.\n",
        RADII.0, RADII.1, STOP
    );
    // The binary lives in target/release: the venv and the exchange files
    // go beside it under target/.
    let exe = std::env::current_exe()?;
    let target = exe
        .parent()
        .and_then(Path::parent)
        .context("shroud-bench is not in a target directory")?;
    let python = python(target);
    if let Err(e) = &python {
        println!("OctoMap + FCL not run: {e:#}\n");
    }
    let files = target.join("peers");
    let mut versions = None;
    println!("| scene | points | method | build (ms, median of runs) | memory (bytes) | 50-sphere query (µs) | unsafe: touching called free (of them: centre inside a solid) | conservative: clear called blocked |");
    println!("|---|---:|---|---:|---:|---:|---:|---:|");
    for (index, scene) in [table_top(), moving_spheres()].iter().enumerate() {
        let spheres = scene.spheres(27 + index as u64);
        let touching = spheres.iter().filter(|s| s.touching).count();
        let inside = spheres.iter().filter(|s| s.inside).count();
        let clear = spheres.len() - touching;
        for &rays in sizes {
            let sensor = scene.sensor(rays);
            let points = sensor.scan(&scene.solids).points;
            let mut rows = shroud_rows(&points, &spheres, runs, MAX_REFINE_DEPTH)?;
            let shroud_conservative = score(&rows[0].blocked, &spheres).2;
            rows.push(elevation_row(20, "equal grid", &points, &spheres, runs)?);
            let grid = matching_grid(&points, &spheres, shroud_conservative);
            rows.push(elevation_row(
                grid,
                "coarsest as tight as shroud",
                &points,
                &spheres,
                runs,
            )?);
            if let Ok(py) = &python {
                let dir = files.join(format!("{}-{}", index, points.len()));
                match octomap_rows(py, &dir, &points, sensor.origin, &spheres, args) {
                    Ok((more, v)) => {
                        rows.extend(more);
                        versions = Some(v);
                    }
                    Err(e) => bail!(
                        "OctoMap + FCL on {} ({} points): {e:#}",
                        scene.name,
                        points.len()
                    ),
                }
            }
            for row in rows {
                let (unsafe_, unseen, conservative) = score(&row.blocked, &spheres);
                println!(
                    "| {} | {}K | {} | {:.2} ({}) | {} | {:.0} | {unsafe_} of {touching} ({unseen} of {inside}) | {conservative} of {clear} |",
                    scene.name,
                    points.len() / 1000,
                    row.method,
                    row.build_ms,
                    row.runs,
                    row.bytes,
                    row.query_us,
                );
            }
        }
    }
    if let Some(v) = versions {
        println!("\nOctoMap + FCL: {v}; build = insertion alone (the hand-over to FCL, a binary copy the Python bindings need, is in the method's name).");
    }
    println!();
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Parses a `.npy` file as `npy_bytes` writes it: the header's text and
    /// the little-endian values.
    fn parse(bytes: &[u8]) -> (String, Vec<u8>) {
        assert_eq!(&bytes[..8], b"\x93NUMPY\x01\x00");
        let len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
        assert_eq!((10 + len) % 64, 0);
        let header = String::from_utf8(bytes[10..10 + len].to_vec()).unwrap();
        (header, bytes[10 + len..].to_vec())
    }

    #[test]
    fn npy_files_round_trip() {
        let values = [1.5f32, -2.25, 3.0, 0.1, 1e-30, f32::MAX];
        let (header, data) = parse(&npy_bytes(&[2, 3], &values));
        assert!(header.starts_with("{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }"));
        assert!(header.ends_with('\n'));
        let back: Vec<f32> = data
            .chunks(4)
            .map(|c| f32::from_le_bytes(c.try_into().unwrap()))
            .collect();
        assert_eq!(back, values);
        let (header, data) = parse(&npy_bytes(&[3], &[0.5f64, -7.0, 1e300]));
        assert!(header.contains("'descr': '<f8'") && header.contains("'shape': (3,)"));
        let back: Vec<f64> = data
            .chunks(8)
            .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
            .collect();
        assert_eq!(back, [0.5, -7.0, 1e300]);
    }
}
