//! End-to-end tests of the `shroud` binary: real processes, real files.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn shroud(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_shroud"))
        .args(args)
        .output()
        .expect("the shroud binary runs")
}

fn text(out: &Output) -> (String, String) {
    (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn path(dir: &Path, name: &str) -> PathBuf {
    dir.join(name)
}

fn s(p: &Path) -> &str {
    p.to_str().expect("utf-8 temp path")
}

/// Writes `bytes` to the file `name` in `dir`.
fn write_file(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let p = path(dir, name);
    std::fs::write(&p, bytes).unwrap();
    p
}

/// Fails with both streams shown unless the command succeeded.
fn ok(out: Output) -> String {
    let (stdout, stderr) = text(&out);
    assert!(out.status.success(), "failed: {stdout}\n{stderr}");
    stdout
}

/// The (final) RMSE that `shroud smooth` prints.
fn rmse_of(stdout: &str) -> f64 {
    stdout
        .lines()
        .find(|l| l.starts_with("errors:"))
        .and_then(|l| l.split("RMSE ").nth(1))
        .and_then(|r| r.trim().parse().ok())
        .unwrap_or_else(|| panic!("no RMSE in {stdout}"))
}

/// Asserts a clean failure: non-zero exit, an error naming `needle`, no panic.
fn fails_with(out: Output, needle: &str) {
    let (stdout, stderr) = text(&out);
    assert!(!out.status.success(), "unexpected success: {stdout}");
    assert!(!stderr.contains("panicked"), "panic: {stderr}");
    assert!(
        stderr.to_lowercase().contains(&needle.to_lowercase()),
        "expected '{needle}' in: {stderr}"
    );
}

#[test]
fn sim_then_fit_prints_a_certificate_and_writes_files() {
    let dir = tempfile::tempdir().unwrap();
    let cloud = path(dir.path(), "cloud.ply");
    ok(shroud(&[
        "sim",
        "moving-spheres",
        "--points",
        "20000",
        "--time",
        "0.5",
        "-o",
        s(&cloud),
    ]));
    for (side, expected) in [("upper", 1), ("lower", 1), ("sandwich", 2)] {
        let out = path(dir.path(), &format!("{side}.json"));
        let mesh = path(dir.path(), &format!("{side}.obj"));
        let stdout = ok(shroud(&[
            "fit",
            s(&cloud),
            "--grid",
            "20x14",
            "--dir",
            "0.2,-0.1,-1",
            "--side",
            side,
            "-o",
            s(&out),
            "--mesh",
            s(&mesh),
        ]));
        assert_eq!(
            stdout.matches("20000 points checked, 0 violations").count(),
            expected,
            "{stdout}"
        );
        let json: serde_json::Value =
            serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
        assert_eq!(json["format"], "shroud-surrogate");
        let obj = std::fs::read_to_string(&mesh).unwrap();
        assert!(
            obj.lines().any(|l| l.starts_with("v ")) && obj.lines().any(|l| l.starts_with("f "))
        );
    }
}

#[test]
fn binary_surrogate_and_xyz_input_and_query() {
    let dir = tempfile::tempdir().unwrap();
    let cloud = path(dir.path(), "terrain.xyz");
    ok(shroud(&[
        "sim",
        "terrain",
        "--points",
        // Dense enough that every cell triangle holds points: an empty one
        // is trimmed (space the sensor did not see).
        "30000",
        "-o",
        s(&cloud),
    ]));
    let surrogate = path(dir.path(), "terrain.shrd");
    ok(shroud(&[
        "fit",
        s(&cloud),
        "--side",
        "sandwich",
        "--tight",
        "-o",
        s(&surrogate),
    ]));
    // A point far above the terrain is above the upper surface.
    let stdout = ok(shroud(&["query", s(&surrogate), "--point", "0,0,100"]));
    assert!(stdout.contains("above"), "{stdout}");
    // A ray straight down from above hits the upper surface first.
    let stdout = ok(shroud(&[
        "query",
        s(&surrogate),
        "--ray",
        "0.5,0.5,50,0,0,-1",
    ]));
    assert!(stdout.contains("hit"), "{stdout}");
    let stdout = ok(shroud(&[
        "query",
        s(&surrogate),
        "--ray",
        "0.5,0.5,50,0,0,1",
    ]));
    assert!(stdout.contains("no hit"), "{stdout}");
}

#[test]
fn bad_clouds_get_clear_errors() {
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, bytes: &[u8]| write_file(dir.path(), name, bytes);
    fails_with(shroud(&["fit", s(&write("empty.xyz", b""))]), "empty");
    fails_with(
        shroud(&["fit", s(&write("nan.xyz", b"0 0 0\n1 nan 2\n3 4 5\n"))]),
        "non-finite",
    );
    fails_with(
        shroud(&["fit", s(&write("inf.csv", b"x,y,z\n0,0,0\n1,inf,2\n"))]),
        "non-finite",
    );
    fails_with(
        shroud(&["fit", s(&write("same.xyz", b"1 2 3\n1 2 3\n1 2 3\n"))]),
        "degenerate",
    );
    fails_with(
        shroud(&["fit", s(&write("line.xyz", b"0 0 0\n1 1 1\n2 2 2\n"))]),
        "degenerate",
    );
    fails_with(
        shroud(&["fit", s(&write("words.xyz", b"0 0 0\nhello world\n"))]),
        "line 2",
    );
    let header = b"ply\nformat binary_little_endian 1.0\nelement vertex 10\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
    let mut truncated = header.to_vec();
    truncated.extend_from_slice(&[0u8; 50]);
    fails_with(
        shroud(&["fit", s(&write("cut.ply", &truncated))]),
        "truncated",
    );
    fails_with(
        shroud(&[
            "fit",
            s(&write("bad.ply", b"ply\nformat nonsense 1.0\nend_header\n")),
        ]),
        "format",
    );
    fails_with(
        shroud(&["fit", s(&path(dir.path(), "missing.ply"))]),
        "cannot read",
    );
}

#[test]
fn pcd_clouds_are_read_and_written() {
    let dir = tempfile::tempdir().unwrap();
    // A PCL-style organised cloud (4 x 3, binary, `_` padding) with 3 NaN points.
    let fixture = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/libraries/shapes/tests/data/pcd/organised_nan_binary.pcd"
    );
    let out = shroud(&["fit", fixture, "--grid", "3x3"]);
    let (stdout, stderr) = text(&out);
    assert!(out.status.success(), "{stdout}\n{stderr}");
    assert!(
        stdout.contains("9 points checked, 0 violations"),
        "{stdout}"
    );
    assert!(
        stderr.contains("left out 3 invalid points (NaN coordinates)"),
        "{stderr}"
    );
    // Each encoding, and binary when none is asked for.
    for (flag, encoding) in [
        (Some("ascii"), "ascii"),
        (Some("binary"), "binary"),
        (Some("binary_compressed"), "binary_compressed"),
        (None, "binary"),
    ] {
        let cloud = path(dir.path(), &format!("{}.pcd", flag.unwrap_or("default")));
        let pcd = s(&cloud);
        let mut args = vec!["sim", "terrain", "--points", "3000", "-o", pcd];
        args.extend(flag.map(|f| ["--pcd-encoding", f]).into_iter().flatten());
        ok(shroud(&args));
        let bytes = std::fs::read(&cloud).unwrap();
        let data_line = format!("\nPOINTS 3000\nDATA {encoding}\n");
        assert!(
            bytes
                .windows(data_line.len())
                .any(|w| w == data_line.as_bytes()),
            "{flag:?}"
        );
        let stdout = ok(shroud(&["fit", pcd, "--grid", "8x8"]));
        assert!(
            stdout.contains("3000 points checked, 0 violations"),
            "{stdout}"
        );
    }
    // An encoding for another format, or an unknown one, is refused.
    let cloud = path(dir.path(), "c.pcd");
    fails_with(
        shroud(&[
            "sim",
            "terrain",
            "-o",
            s(&path(dir.path(), "c.ply")),
            "--pcd-encoding",
            "ascii",
        ]),
        "not a .pcd file",
    );
    fails_with(
        shroud(&["sim", "terrain", "-o", s(&cloud), "--pcd-encoding", "lzf"]),
        "expected ascii, binary or binary_compressed",
    );
}

#[test]
fn bad_pcd_files_name_the_problem() {
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, bytes: &[u8]| write_file(dir.path(), name, bytes);
    let mut truncated = b"VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n\
        WIDTH 10\nHEIGHT 1\nPOINTS 10\nDATA binary\n"
        .to_vec();
    let body = truncated.len();
    truncated.extend_from_slice(&[0u8; 50]);
    fails_with(
        shroud(&["fit", s(&write("cut.pcd", &truncated))]),
        &format!(
            "point 4 field 'x' needs 4 bytes at offset {}, only 2 remain",
            body + 48
        ),
    );
    fails_with(
        shroud(&[
            "fit",
            s(&write(
                "noz.pcd",
                b"FIELDS x y\nPOINTS 1\nDATA ascii\n1 2\n",
            )),
        ]),
        "no 'z' field",
    );
    // An unknown extension is sniffed: this is PCD, and its line 3 is wrong.
    fails_with(
        shroud(&[
            "fit",
            s(&write(
                "scan.dat",
                b"# .PCD v0.7\nFIELDS x y z\nPOINTS 2\nDATA ascii\n1 2 3\n4 5 x\n",
            )),
        ]),
        "line 6 (point 1): field 'z' is 'x', not a number",
    );
    let all_nan =
        b"FIELDS x y z\nWIDTH 2\nHEIGHT 1\nPOINTS 2\nDATA ascii\nnan nan nan\nnan nan nan\n";
    fails_with(
        shroud(&["fit", s(&write("nan.pcd", all_nan))]),
        "all 2 points of the PCD file are invalid",
    );
}

#[test]
fn bad_options_get_clear_errors() {
    let dir = tempfile::tempdir().unwrap();
    let cloud = path(dir.path(), "c.ply");
    ok(shroud(&[
        "sim",
        "table-top",
        "--points",
        "2000",
        "-o",
        s(&cloud),
    ]));
    fails_with(shroud(&["fit", s(&cloud), "--dir", "0,0,0"]), "direction");
    fails_with(
        shroud(&["fit", s(&cloud), "--dir", "0,0"]),
        "3 comma-separated",
    );
    fails_with(
        shroud(&["fit", s(&cloud), "--grid", "1x5"]),
        "at least 2 x 2",
    );
    fails_with(shroud(&["fit", s(&cloud), "--grid", "twenty"]), "grid");
    fails_with(shroud(&["sim", "volcano", "-o", s(&cloud)]), "volcano");
    fails_with(
        shroud(&["sim", "terrain", "--points", "0", "-o", s(&cloud)]),
        "points",
    );
}

#[test]
fn corrupted_surrogates_are_rejected() {
    let dir = tempfile::tempdir().unwrap();
    let cloud = path(dir.path(), "c.ply");
    ok(shroud(&[
        "sim",
        "moving-spheres",
        "--points",
        "3000",
        "-o",
        s(&cloud),
    ]));
    let good = path(dir.path(), "s.shrd");
    ok(shroud(&["fit", s(&cloud), "-o", s(&good)]));
    let mut bytes = std::fs::read(&good).unwrap();
    let middle = bytes.len() / 2;
    bytes[middle] ^= 0x55;
    let bad = path(dir.path(), "bad.shrd");
    std::fs::write(&bad, &bytes).unwrap();
    fails_with(shroud(&["query", s(&bad), "--point", "0,0,0"]), "surrogate");
    std::fs::write(&bad, &bytes[..10]).unwrap();
    fails_with(shroud(&["query", s(&bad), "--point", "0,0,0"]), "surrogate");
}

#[test]
fn bench_quick_prints_the_paper_tables() {
    let bench = common::bench::shroud_bench()
        .args(["surrogate", "--quick"])
        .output()
        .expect("the shroud-bench binary runs");
    let stdout = ok(bench);
    for heading in ["Table 1", "Table 2", "Figure 9", "Section 3"] {
        assert!(
            stdout.contains(heading),
            "{heading} missing from:\n{stdout}"
        );
    }
    assert!(stdout.contains("| 10K | 14.5 |"), "{stdout}");
}

/// The benchmarks are their own binary, `shroud-bench`; the shipped one has none.
#[test]
fn the_shipped_binary_has_no_bench_subcommand() {
    fails_with(
        shroud(&["bench", "surrogate", "--quick"]),
        "unrecognized subcommand 'bench'",
    );
}

#[test]
fn smooth_info_prints_the_classification_and_the_g1_dimension() {
    let dir = tempfile::tempdir().unwrap();
    // The paper's M_T: a triangle split into three quads around a valence-3 EV.
    let m_t = path(dir.path(), "m_t.obj");
    std::fs::write(
        &m_t,
        "v 0 0 0\nv 2 0 0\nv 1 1.732 0\nv 1 0 0\nv 1.5 0.866 0\nv 0.5 0.866 0\nv 1 0.577 0\n\
         f 1 4 7 6\nf 2 5 7 4\nf 3 6 7 5\n",
    )
    .unwrap();
    let stdout = ok(shroud(&["smooth", "--mesh", s(&m_t), "--info"]));
    assert!(stdout.contains("dimension: 72"), "{stdout}");
    assert!(stdout.contains("basis: 72 functions"), "{stdout}");
    assert!(stdout.contains("inner extraordinary 1"), "{stdout}");
    assert!(!stdout.contains("refined once"), "{stdout}");
    // A cube: adjacent EVs, refined once and told so (24 faces).
    let cube = path(dir.path(), "cube.obj");
    std::fs::write(
        &cube,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n\
         f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n",
    )
    .unwrap();
    let stdout = ok(shroud(&["smooth", "--mesh", s(&cube), "--info"]));
    assert!(stdout.contains("refined once"), "{stdout}");
    assert!(stdout.contains("faces: 24"), "{stdout}");
    // An L of three quads has a boundary EV (kappa = 3): its basis has the
    // N + 2 = 6 vertex functions of Section 4.1.3.
    let l_shape = path(dir.path(), "l.obj");
    std::fs::write(
        &l_shape,
        "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\nv 0 2 0\nv 1 2 0\n\
         f 1 2 5 4\nf 2 3 6 5\nf 4 5 8 7\n",
    )
    .unwrap();
    let stdout = ok(shroud(&["smooth", "--mesh", s(&l_shape), "--info"]));
    assert!(stdout.contains("dimension: 82"), "{stdout}");
    assert!(stdout.contains("basis: 82 functions"), "{stdout}");
    assert!(stdout.contains("matches the dimension"), "{stdout}");
    // Bad meshes are named errors.
    let bad = path(dir.path(), "tri.obj");
    std::fs::write(&bad, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    fails_with(shroud(&["smooth", "--mesh", s(&bad), "--info"]), "tri.obj");
    std::fs::write(&bad, "").unwrap();
    fails_with(shroud(&["smooth", "--mesh", s(&bad), "--info"]), "tri.obj");
    fails_with(
        shroud(&["smooth", "--mesh", "/nonexistent.obj", "--info"]),
        "cannot read",
    );
}

#[test]
fn smooth_fits_a_graph_over_a_planar_domain() {
    let dir = tempfile::tempdir().unwrap();
    let m_t = path(dir.path(), "m_t.obj");
    std::fs::write(
        &m_t,
        "v 0 0 0\nv 2 0 0\nv 1 1.7320508 0\nv 1 0 0\nv 1.5 0.8660254 0\nv 0.5 0.8660254 0\nv 1 0.57735027 0\n\
         f 1 4 7 6\nf 2 5 7 4\nf 3 6 7 5\n",
    )
    .unwrap();
    // A smooth graph sampled inside the triangle (0,0), (2,0), (1, sqrt 3).
    let mut text = String::new();
    let n = 60;
    for a in 0..=n {
        for b in 0..=(n - a) {
            let (s, t) = (a as f64 / n as f64, b as f64 / n as f64);
            let (x, y) = (2.0 * s + t, 3f64.sqrt() * t);
            let (x, y) = (0.98 * x + 0.02, 0.98 * y + 0.005); // strictly inside
            text += &format!("{x} {y} {}\n", 0.3 * x * y + 0.1 * y * y);
        }
    }
    let cloud = path(dir.path(), "graph.xyz");
    std::fs::write(&cloud, &text).unwrap();
    let out = path(dir.path(), "fit.obj");
    let stdout = ok(shroud(&[
        "smooth",
        s(&cloud),
        "--mesh",
        s(&m_t),
        "-o",
        s(&out),
    ]));
    assert!(stdout.contains("with 72 G1 functions"), "{stdout}");
    let rmse = rmse_of(&stdout);
    assert!(rmse < 1e-2, "{stdout}");
    assert!(std::fs::read_to_string(&out).unwrap().contains("\nf "));
    let json = path(dir.path(), "fit.json");
    ok(shroud(&[
        "smooth",
        s(&cloud),
        "--mesh",
        s(&m_t),
        "--lambda",
        "1e-4",
        "-o",
        s(&json),
    ]));
    let patches: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    assert_eq!(patches["patches"].as_array().unwrap().len(), 3);

    // A point outside the domain, too few points, and a bad lambda are errors.
    let outside = path(dir.path(), "outside.xyz");
    std::fs::write(&outside, format!("{text}5 5 0\n")).unwrap();
    fails_with(
        shroud(&["smooth", s(&outside), "--mesh", s(&m_t)]),
        "outside the planar domain",
    );
    let few = path(dir.path(), "few.xyz");
    std::fs::write(&few, "0.5 0.2 0\n1 0.5 0\n1.5 0.2 0\n").unwrap();
    fails_with(shroud(&["smooth", s(&few), "--mesh", s(&m_t)]), "singular");
    fails_with(
        shroud(&["smooth", s(&cloud), "--mesh", s(&m_t), "--lambda", "-1"]),
        "lambda",
    );
    fails_with(shroud(&["smooth", "--mesh", s(&m_t)]), "--info");
}

#[test]
fn smooth_fits_a_radial_function_over_the_sphere() {
    let dir = tempfile::tempdir().unwrap();
    let n = 6000;
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let mut text = String::new();
    for i in 0..n {
        let z = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
        let r = (1.0 - z * z).sqrt();
        let a = golden * i as f64;
        let radius = 1.0 + 0.1 * z;
        text += &format!(
            "{} {} {}\n",
            radius * r * a.cos(),
            radius * r * a.sin(),
            radius * z
        );
    }
    let cloud = path(dir.path(), "blob.xyz");
    std::fs::write(&cloud, &text).unwrap();
    let out = path(dir.path(), "blob.obj");
    let stdout = ok(shroud(&[
        "smooth",
        s(&cloud),
        "--domain",
        "sphere:1",
        "-o",
        s(&out),
    ]));
    assert!(stdout.contains("G1 functions on 24 patches"), "{stdout}");
    let rmse = rmse_of(&stdout);
    assert!(rmse < 1e-3, "{stdout}");
    fails_with(
        shroud(&["smooth", s(&cloud), "--domain", "torus"]),
        "expected sphere",
    );
    fails_with(
        shroud(&["smooth", s(&cloud), "--domain", "sphere:9"]),
        "LEVELS",
    );
    let origin = path(dir.path(), "origin.xyz");
    std::fs::write(&origin, format!("{text}0 0 0\n")).unwrap();
    fails_with(
        shroud(&["smooth", s(&origin), "--domain", "sphere"]),
        "no direction",
    );
}

/// Points on the sphere of radius `r` around `c`, by a Fibonacci lattice.
fn sphere_xyz(n: usize, c: [f64; 3], r: f64) -> String {
    shroud_geometry::math::fibonacci_sphere(n)
        .iter()
        .map(|d| {
            let p = glam::DVec3::from_array(c) + r * *d;
            format!("{} {} {}\n", p.x, p.y, p.z)
        })
        .collect()
}

#[test]
fn smooth_fits_a_parametric_surface_over_a_mesh_in_space() {
    let dir = tempfile::tempdir().unwrap();
    // A sphere (a closed surface, not a graph) over a coarse quad mesh of it:
    // the inscribed cube, refined once since its EVs touch.
    let cube = path(dir.path(), "cube.obj");
    std::fs::write(&cube, common::inscribed_cube_obj()).unwrap();
    let cloud = path(dir.path(), "ball.xyz");
    std::fs::write(&cloud, sphere_xyz(8000, [0.5, 0.5, 0.5], 0.7)).unwrap();
    let out = path(dir.path(), "ball.ply");
    let patches = path(dir.path(), "ball.json");
    let stdout = ok(shroud(&[
        "smooth",
        s(&cloud),
        "--mesh",
        s(&cube),
        "-o",
        s(&out),
        "-o",
        s(&patches),
    ]));
    assert!(stdout.contains("(parametric)"), "{stdout}");
    assert!(stdout.contains("refined once"), "{stdout}");
    let first: f64 = stdout
        .lines()
        .find(|l| l.starts_with("after 0 corrections"))
        .and_then(|l| l.rsplit("RMSE").next())
        .and_then(|x| x.trim().parse().ok())
        .unwrap_or_else(|| panic!("no first round in:\n{stdout}"));
    assert!(stdout.contains("after 2 corrections"), "{stdout}");
    let last = rmse_of(&stdout);
    assert!(last < first / 10.0 && last < 5e-4, "{stdout}");
    assert!(std::fs::read(&out).unwrap().starts_with(b"ply\n"));
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&patches).unwrap()).unwrap();
    assert_eq!(
        (json["kind"].as_str(), json["dim"].as_u64()),
        (Some("parametric"), Some(3))
    );
    assert_eq!(json["patches"][0].as_array().unwrap().len(), 36 * 3);
    fails_with(
        shroud(&["smooth", s(&cloud), "--mesh", s(&cube), "-o", "fit.stl"]),
        "must be .json, .obj or .ply",
    );
    // No corrections on request; a graph takes none.
    let stdout = ok(shroud(&[
        "smooth",
        s(&cloud),
        "--mesh",
        s(&cube),
        "--corrections",
        "0",
    ]));
    assert!(!stdout.contains("after 0 corrections"), "{stdout}");
    fails_with(
        shroud(&[
            "smooth",
            s(&cloud),
            "--domain",
            "sphere:1",
            "--corrections",
            "2",
        ]),
        "parametric",
    );
    let bad = path(dir.path(), "nan.xyz");
    std::fs::write(&bad, "0 0 0\nnan 1 1\n").unwrap();
    fails_with(
        shroud(&["smooth", s(&bad), "--mesh", s(&cube)]),
        "non-finite coordinate",
    );
}

#[test]
fn smooth_fits_a_graph_over_a_rectangle_domain() {
    let dir = tempfile::tempdir().unwrap();
    let mut text = String::new();
    for i in 0..80 {
        for j in 0..60 {
            let (x, y) = (
                -1.0 + 3.0 * (i as f64 + 0.5) / 80.0,
                2.0 * (j as f64 + 0.5) / 60.0,
            );
            text += &format!("{x} {y} {}\n", (x * 1.3).sin() * y);
        }
    }
    let cloud = path(dir.path(), "terrain.xyz");
    std::fs::write(&cloud, &text).unwrap();
    let stdout = ok(shroud(&[
        "smooth",
        s(&cloud),
        "--domain",
        "plane:-1,0,2,2,3",
    ]));
    // A 3 x 3 grid: the C1 biquintic space, (4 * 3 + 2)^2 functions.
    assert!(
        stdout.contains("with 196 G1 functions on 9 patches"),
        "{stdout}"
    );
    assert!(rmse_of(&stdout) < 1e-3, "{stdout}");
    let stdout = ok(shroud(&["smooth", "--domain", "plane:0,0,1,1", "--info"]));
    assert!(stdout.contains("dimension: 324"), "{stdout}");
    for bad in [
        "plane:1,0,0,1",
        "plane:0,0,1",
        "plane:0,0,1,1,0",
        "plane:a,b,c,d",
    ] {
        fails_with(shroud(&["smooth", s(&cloud), "--domain", bad]), bad);
    }
    fails_with(
        shroud(&["smooth", s(&cloud), "--domain", "plane:0,0,1,1"]),
        "outside the planar domain",
    );
}

#[test]
fn limit_surface_clouds_fit_over_their_own_quad_mesh() {
    // Paper 004, Section 6.2 in small: a cloud of the ring's Catmull-Clark
    // limit surface, fitted in R^3 over the ring's quads.
    let dir = tempfile::tempdir().unwrap();
    let cloud = path(dir.path(), "ring.ply");
    let quads = path(dir.path(), "ring.obj");
    let stdout = ok(shroud(&[
        "sim",
        "limit-surface",
        "--quads",
        "ring",
        "--points",
        "30000",
        "--write-quads",
        s(&quads),
        "-o",
        s(&cloud),
    ]));
    assert!(
        stdout.contains("30000 points of the limit surface of ring (32 quads)"),
        "{stdout}"
    );
    let stdout = ok(shroud(&["smooth", s(&cloud), "--mesh", s(&quads)]));
    assert!(stdout.contains("(parametric)"), "{stdout}");
    // The ring is 3 x 3 x 1: errors small against its size.
    assert!(rmse_of(&stdout) < 2e-3, "{stdout}");
    fails_with(
        shroud(&["sim", "limit-surface", "-o", s(&cloud)]),
        "--quads",
    );
    fails_with(
        shroud(&[
            "sim",
            "limit-surface",
            "--quads",
            "/nonexistent.obj",
            "-o",
            s(&cloud),
        ]),
        "cannot read",
    );
}

/// Log filters: `--log` wins over RUST_LOG, and a filter that does not parse
/// is a named error wherever it comes from, never a silent fallback.
#[test]
fn bad_log_filters_are_named_errors() {
    fails_with(
        shroud(&["--log", "shroud=loud", "node", "list"]),
        "invalid log filter \"shroud=loud\" from --log",
    );
    let from_env = Command::new(env!("CARGO_BIN_EXE_shroud"))
        .args(["node", "list"])
        .env("RUST_LOG", "shroud=loud")
        .output()
        .unwrap();
    fails_with(from_env, "from RUST_LOG");
    let overridden = Command::new(env!("CARGO_BIN_EXE_shroud"))
        .args(["--log", "warn", "sim", "moving-spheres", "--points", "100"])
        .args(["-o", "/dev/null/none.ply"])
        .env("RUST_LOG", "shroud=loud")
        .output()
        .unwrap();
    let (_, stderr) = text(&overridden);
    assert!(!stderr.contains("invalid log filter"), "{stderr}");
    let dir = tempfile::tempdir().unwrap();
    let file = path(dir.path(), "g.toml");
    std::fs::write(&file, "[[node]]\nname = \"x\"\nkind = \"fit\"\n").unwrap();
    fails_with(
        shroud(&["launch", s(&file), "--node-log", "x=loud", "--check"]),
        "invalid --node-log filter",
    );
}

/// The guard's tolerances are checked before it starts: each bad value is a
/// named error and a non-zero exit.
#[test]
fn bad_guard_settings_are_named_errors() {
    let arm = concat!(env!("CARGO_MANIFEST_DIR"), "/launch/arms/demo_arm.toml");
    let guard = |extra: &[&str]| {
        let mut args = vec!["node", "guard", "--arm-file", arm];
        args.extend_from_slice(extra);
        shroud(&args)
    };
    fails_with(guard(&["--max-skew", "0"]), "--max-skew");
    fails_with(guard(&["--max-age", "nan"]), "--max-age");
    fails_with(guard(&["--max-obstacle-speed=-1"]), "max_obstacle_speed");
    fails_with(guard(&["--unobserved", "maybe"]), "--unobserved");
    fails_with(guard(&["--sectors", "9"]), "--sectors");
    fails_with(
        guard(&["--sectors", "2", "--unobserved", "ignore"]),
        "--sectors needs --unobserved stop",
    );
    fails_with(
        guard(&["--surrogate", "cam.s3", "--unobserved", "ignore"]),
        "is a sector's stream",
    );
    fails_with(shroud(&["node", "fit", "--sectors", "9"]), "--sectors");
    fails_with(
        shroud(&["node", "fit", "--sectors", "2", "--sector-reach", "0.5"]),
        "sector reach 0.5",
    );
    fails_with(
        guard(&["--surrogate", "a", "--surrogate", "a"]),
        "given twice",
    );
    fails_with(
        shroud(&["node", "arm", "--arm-file", arm, "--resume-after=-1"]),
        "--resume-after",
    );
}

/// `shroud mcap info` and `shroud replay` refuse files that are not MCAP
/// recordings, and `shroud record` its bad options, before anything starts:
/// each a named error and a non-zero exit.
#[test]
fn bad_recordings_and_recording_options_are_named_errors() {
    let dir = tempfile::tempdir().unwrap();
    let missing = path(dir.path(), "missing.mcap");
    let empty = write_file(dir.path(), "empty.mcap", b"");
    let foreign = write_file(
        dir.path(),
        "cloud.mcap",
        b"ply\nformat ascii 1.0\nend_header\n",
    );
    for command in [&["mcap", "info"][..], &["replay"][..]] {
        let run = |file: &Path| shroud(&[command, &[s(file)]].concat());
        fails_with(run(&missing), "cannot open");
        fails_with(run(&empty), "is empty");
        fails_with(run(&foreign), "not an MCAP file");
    }
    let out = s(&path(dir.path(), "run.mcap")).to_owned();
    let record = |extra: &[&str]| shroud(&[&["record", "-o", &out][..], extra].concat());
    fails_with(record(&["--topics", "clouds/*"]), "not a topic kind");
    fails_with(record(&["--topics", "cloud/[ab]"]), "--topics");
    fails_with(record(&["--topics", "alive/*"]), "liveliness");
    fails_with(record(&["--split-size", "0"]), "--split-size");
    fails_with(record(&["--split-size", "1e12"]), "--split-size");
    fails_with(record(&["--duration=-1"]), "--duration");
    fails_with(record(&["--queue-size", "0"]), "--queue-size");
    fails_with(record(&["--points-budget", "5"]), "--points-budget");
    fails_with(record(&["--verdict-timeout", "0"]), "--verdict-timeout");
    fails_with(record(&["--foxglove", "maybe"]), "--foxglove");
    fails_with(
        record(&["--arm-file", "/no/such/arm.toml"]),
        "/no/such/arm.toml",
    );
    let taken = write_file(dir.path(), "taken.mcap", b"x");
    fails_with(
        shroud(&["record", "-o", s(&taken)]),
        "exists (give --overwrite",
    );
    fails_with(
        shroud(&["record", "-o", "/no/such/dir/run.mcap"]),
        "cannot create",
    );
    fails_with(shroud(&["replay", s(&missing), "--speed", "0"]), "--speed");
}
