//! End-to-end test of the `smooth` node (paper 004): a scanner publishes the
//! terrain, the node fits it by G1 smooth patches over a planar grid domain
//! and publishes them with their error measures.

mod common;

use common::{assert_all_gone, free_port, hub, wiring, Proc};
use shroud_msg::{CloudMessage, NodeStatusMessage, SmoothPatchesMessage};
use std::time::{Duration, Instant};
use zenoh::Wait;

const LONG: Duration = Duration::from_secs(90);

/// A 4 x 3 grid of 2 x 2 quads over the terrain's [-4, 4] x [-3, 3].
fn grid_obj() -> String {
    let mut text = String::new();
    for j in 0..4 {
        for i in 0..5 {
            text += &format!("v {} {} 0\n", -4.0 + 2.0 * i as f64, -3.0 + 2.0 * j as f64);
        }
    }
    for j in 0..3 {
        for i in 0..4 {
            let v = |a: usize, b: usize| b * 5 + a + 1;
            text += &format!(
                "f {} {} {} {}\n",
                v(i, j),
                v(i + 1, j),
                v(i + 1, j + 1),
                v(i, j + 1)
            );
        }
    }
    text
}

#[test]
fn smooth_node_fits_the_terrain_and_survives_garbage() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = dir.path().join("grid.obj");
    std::fs::write(&mesh, grid_obj()).unwrap();
    let endpoint = format!("tcp/127.0.0.1:{}", free_port());
    let session = hub(&endpoint);
    let ns = "e2e-smooth";
    let patches = session
        .declare_subscriber(format!("shroud/{ns}/smooth/terrain"))
        .wait()
        .unwrap();
    let statuses = session
        .declare_subscriber(format!("shroud/{ns}/status/smooth"))
        .wait()
        .unwrap();
    let w = wiring(&endpoint, ns);
    let mesh_arg = mesh.to_str().unwrap();
    let mut node = Proc::start(
        &[
            &["node", "smooth", "--input", "terrain", "--mesh", mesh_arg][..],
            &w,
        ]
        .concat(),
    );
    let mut scanner = Proc::start(
        &[
            &[
                "node", "scanner", "--scene", "terrain", "--points", "8000", "--rate", "5",
                "--stream", "terrain",
            ][..],
            &w,
        ]
        .concat(),
    );
    let sample = patches
        .recv_timeout(LONG)
        .unwrap()
        .unwrap_or_else(|| panic!("no patches; node:\n{}", node.output()));
    let msg = SmoothPatchesMessage::from_bytes(&sample.payload().to_bytes()).unwrap();
    assert_eq!(msg.kind, "graph");
    assert_eq!(msg.functions, 18 * 14, "(4n + 2)(4m + 2) on a 4 x 3 grid");
    assert_eq!(msg.quads.len(), 12 * 16);
    assert!(msg.points > 7_000, "{}", msg.points);
    // Terrain with cliffs: a smooth fit is close but not exact.
    assert!(
        msg.error_rmse > 0.0 && msg.error_rmse < 0.5,
        "{}",
        msg.error_rmse
    );

    // Garbage on the input is counted; the node keeps fitting.
    let key = format!("shroud/{ns}/cloud/terrain");
    for payload in [b"garbage".to_vec(), Vec::new()] {
        session.put(&key, payload).wait().unwrap();
        std::thread::sleep(Duration::from_millis(50));
    }
    let deadline = Instant::now() + LONG;
    loop {
        assert!(
            Instant::now() < deadline,
            "garbage not counted:\n{}",
            node.output()
        );
        if let Ok(Some(s)) = statuses.recv_timeout(Duration::from_millis(500)) {
            let status = NodeStatusMessage::from_bytes(&s.payload().to_bytes()).unwrap();
            if status.counter("dropped_malformed") >= 1 {
                break;
            }
        }
    }
    patches.drain().for_each(drop);
    patches
        .recv_timeout(LONG)
        .unwrap()
        .expect("still publishing after garbage");

    let pids = [node.pid(), scanner.pid()];
    node.signal(libc::SIGTERM);
    scanner.signal(libc::SIGTERM);
    assert!(node.wait_exit(LONG).success(), "{}", node.output());
    assert!(scanner.wait_exit(LONG).success(), "{}", scanner.output());
    assert!(!node.output().contains("panicked"), "{}", node.output());
    assert_all_gone(&pids, Duration::from_secs(5));
}

/// A ball of radius 0.7 around (0.5, 0.5, 0.5), and the inscribed cube as
/// its coarse quad mesh: a parametric fit with parameter correction.
#[test]
fn smooth_node_fits_a_closed_surface_in_space() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = dir.path().join("cube.obj");
    std::fs::write(&mesh, common::inscribed_cube_obj()).unwrap();
    let endpoint = format!("tcp/127.0.0.1:{}", free_port());
    let session = hub(&endpoint);
    let ns = "e2e-smooth-ball";
    let patches = session
        .declare_subscriber(format!("shroud/{ns}/smooth/ball"))
        .wait()
        .unwrap();
    let w = wiring(&endpoint, ns);
    let args = [
        "node", "smooth", "--input", "ball", "--lambda", "0", "--mesh",
    ];
    let mut node = Proc::start(&[&args[..], &[mesh.to_str().unwrap()], &w].concat());
    let ball: Vec<[f32; 3]> = shroud_geometry::math::fibonacci_sphere(6000)
        .iter()
        .map(|d| (glam::DVec3::splat(0.5) + 0.7 * *d).as_vec3().to_array())
        .collect();
    let cloud = CloudMessage::new(1, 1, "test", Default::default(), &ball)
        .to_bytes()
        .unwrap();
    let key = format!("shroud/{ns}/cloud/ball");
    // The node may not be subscribed yet: publish until patches come back.
    let deadline = Instant::now() + LONG;
    let sample = loop {
        assert!(Instant::now() < deadline, "no patches:\n{}", node.output());
        session.put(&key, cloud.clone()).wait().unwrap();
        if let Ok(Some(sample)) = patches.recv_timeout(Duration::from_secs(2)) {
            break sample;
        }
    };
    let msg = SmoothPatchesMessage::from_bytes(&sample.payload().to_bytes()).unwrap();
    assert_eq!((msg.kind.as_str(), msg.dim), ("parametric", 3));
    assert_eq!(msg.functions, 360, "the cube refined once");
    assert_eq!(msg.points, 6000);
    assert!(msg.error_rmse < 1e-3, "{}", msg.error_rmse);
    // The same object again: each fit starts from the last one's surface, so
    // the error keeps falling (a cold start would repeat it exactly).
    let mut later = msg.error_rmse;
    for _ in 0..2 {
        patches.drain().for_each(drop);
        session.put(&key, cloud.clone()).wait().unwrap();
        let sample = patches
            .recv_timeout(LONG)
            .unwrap()
            .unwrap_or_else(|| panic!("no patches:\n{}", node.output()));
        later = SmoothPatchesMessage::from_bytes(&sample.payload().to_bytes())
            .unwrap()
            .error_rmse;
    }
    assert!(later < msg.error_rmse, "{later} after {}", msg.error_rmse);
    let pid = node.pid();
    node.signal(libc::SIGTERM);
    assert!(node.wait_exit(LONG).success(), "{}", node.output());
    assert_all_gone(&[pid], Duration::from_secs(5));
}
