//! End-to-end tests of the node graph: real `shroud` processes talking over real
//! zenoh sessions on loopback.

mod common;

use common::{alive, assert_all_gone, free_port, hub, hub_on_free_port, wiring, Proc};
use shroud_msg::{CloudMessage, NodeStatusMessage, SurrogateMessage};
use shroud_surrogate::query::{Classify, PointClass, SurrogateView};
use shroud_surrogate::SurrogateWire;
use std::collections::HashMap;
use std::time::{Duration, Instant};
use zenoh::Wait;

const LONG: Duration = Duration::from_secs(60);

/// Clouds from the scanner and surrogates from the fitter arrive; every point of
/// every cloud is checked independently, in f64, against the surrogate that
/// claims to certify it.
#[test]
fn fit_node_publishes_certified_surrogates_and_survives_garbage() {
    let endpoint = format!("tcp/127.0.0.1:{}", free_port());
    let session = hub(&endpoint);
    let ns = "e2e-fit";
    let clouds = session
        .declare_subscriber(format!("shroud/{ns}/cloud/s"))
        .wait()
        .unwrap();
    let surrogates = session
        .declare_subscriber(format!("shroud/{ns}/surrogate/s"))
        .wait()
        .unwrap();
    let statuses = session
        .declare_subscriber(format!("shroud/{ns}/status/fit"))
        .wait()
        .unwrap();
    let w = wiring(&endpoint, ns);
    let mut fit =
        Proc::start(&[&["node", "fit", "--input", "s", "--grid", "12x12"][..], &w].concat());
    let mut scanner = Proc::start(
        &[
            &[
                "node", "scanner", "--points", "3000", "--rate", "20", "--stream", "s",
            ][..],
            &w,
        ]
        .concat(),
    );

    // Certified surrogates arrive and really certify their clouds.
    let mut by_sequence: HashMap<u64, Vec<[f32; 3]>> = HashMap::new();
    let mut verified = 0;
    let deadline = Instant::now() + LONG;
    while verified < 3 {
        assert!(
            Instant::now() < deadline,
            "no certified surrogates; fit:\n{}\nscanner:\n{}",
            fit.output(),
            scanner.output()
        );
        let Ok(Some(sample)) = surrogates.recv_timeout(Duration::from_millis(200)) else {
            continue;
        };
        // The cloud a surrogate certifies was published before it: drain the
        // clouds after the surrogate arrived, not before.
        while let Ok(Some(sample)) = clouds.try_recv() {
            let msg = CloudMessage::from_bytes(&sample.payload().to_bytes()).unwrap();
            by_sequence.insert(msg.sequence, msg.point_array().unwrap());
        }
        let (msg, surrogate) = SurrogateMessage::from_bytes(&sample.payload().to_bytes()).unwrap();
        assert_eq!(msg.surfaces.len(), 2, "a sandwich");
        for s in &msg.surfaces {
            assert_eq!(s.certificate.violations, 0);
            assert_eq!(s.certificate.points_checked, 3000);
        }
        let Some(points) = by_sequence.get(&msg.source_sequence) else {
            continue;
        };
        let view = SurrogateView::new(&surrogate).unwrap();
        for p in points {
            let class = view.classify(glam::DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64));
            assert!(
                matches!(class, PointClass::Between { .. }),
                "point {p:?} of cloud {} is {class:?}",
                msg.source_sequence
            );
        }
        verified += 1;
    }

    // Garbage, truncated and foreign messages on the fitter's input are dropped,
    // logged and counted; the fitter keeps working.
    let cloud_key = format!("shroud/{ns}/cloud/s");
    let valid = CloudMessage::new(1, 1, "x", Default::default(), &[[0.0, 0.0, 0.0]; 10])
        .to_bytes()
        .unwrap();
    let mut wrong_version = CloudMessage::new(1, 1, "x", Default::default(), &[[0.0; 3]]);
    wrong_version.version = 99;
    let bad: Vec<Vec<u8>> = vec![
        b"not msgpack at all".to_vec(),
        valid[..valid.len() / 2].to_vec(),
        wrong_version.to_bytes().unwrap(),
        Vec::new(),
        CloudMessage::new(1, 2, "x", Default::default(), &[[0.0, f32::NAN, 1.0]; 64])
            .to_bytes()
            .unwrap(),
    ];
    for payload in &bad {
        session.put(&cloud_key, payload.clone()).wait().unwrap();
        std::thread::sleep(Duration::from_millis(30));
    }
    let deadline = Instant::now() + LONG;
    loop {
        assert!(
            Instant::now() < deadline,
            "malformed messages not counted; fit:\n{}",
            fit.output()
        );
        if let Ok(Some(sample)) = statuses.recv_timeout(Duration::from_millis(500)) {
            let status = NodeStatusMessage::from_bytes(&sample.payload().to_bytes()).unwrap();
            if status.counter("dropped_malformed") >= bad.len() as u64 - 1 {
                break;
            }
        }
    }
    assert!(
        fit.output().contains("dropped a malformed message"),
        "{}",
        fit.output()
    );
    let before = surrogates.drain().count();
    let _ = before;
    surrogates
        .recv_timeout(Duration::from_secs(20))
        .unwrap()
        .expect("fitter still publishing");

    // SIGTERM stops both cleanly.
    let pids = [fit.pid(), scanner.pid()];
    fit.signal(libc::SIGTERM);
    scanner.signal(libc::SIGTERM);
    assert!(fit.wait_exit(LONG).success(), "{}", fit.output());
    assert!(scanner.wait_exit(LONG).success(), "{}", scanner.output());
    assert!(!fit.output().contains("panicked"));
    assert_all_gone(&pids, Duration::from_secs(5));
    assert!(!alive(pids[0]));
}

/// A scan scene's scanner states its field of view and its rays without a
/// return in every cloud, and the fit node hands both on in the surrogate of
/// that cloud, for the guard to count the space outside the one and inside
/// the other as unseen. Every point of the cloud lies within
/// the stated range of the optical centre, in front of it.
#[test]
fn the_field_of_view_and_empty_rays_travel_from_the_scanner_through_the_fit() {
    let (endpoint, session) = hub_on_free_port();
    let ns = "e2e-fov";
    let clouds = session
        .declare_subscriber(format!("shroud/{ns}/cloud/scan"))
        .wait()
        .unwrap();
    let surrogates = session
        .declare_subscriber(format!("shroud/{ns}/surrogate/scan"))
        .wait()
        .unwrap();
    let w = wiring(&endpoint, ns);
    let fit = Proc::start(
        &[
            &["node", "fit", "--input", "scan", "--grid", "12x12"][..],
            &w,
        ]
        .concat(),
    );
    let scanner = Proc::start(
        &[
            &[
                "node",
                "scanner",
                "--scene",
                "scan-table-top",
                "--points",
                "3000",
                "--rate",
                "10",
                "--stream",
                "scan",
            ][..],
            &w,
        ]
        .concat(),
    );
    let mut stated = HashMap::new();
    let deadline = Instant::now() + LONG;
    let (mut matched, mut surrogates_heard) = (0, 0);
    while matched < 3 {
        assert!(
            Instant::now() < deadline,
            "no surrogate with its cloud's field of view ({} clouds, {surrogates_heard} surrogates); fit:\n{}\nscanner:\n{}",
            stated.len(),
            fit.output(),
            scanner.output()
        );
        let Ok(Some(sample)) = surrogates.recv_timeout(Duration::from_millis(200)) else {
            continue;
        };
        // The cloud a surrogate answers was published before it: drain the
        // clouds after the surrogate arrived.
        while let Ok(Some(cloud)) = clouds.try_recv() {
            let msg = CloudMessage::from_bytes(&cloud.payload().to_bytes()).unwrap();
            let fov = msg.field_of_view.expect("a scan states its field of view");
            let apex = glam::DVec3::from_array(fov.apex);
            let axis = glam::DVec3::from_array(fov.axis);
            for p in msg.point_array().unwrap() {
                let d = glam::DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64) - apex;
                assert!(d.length() <= fov.max_range * (1.0 + 1e-6) && d.dot(axis) > 0.0);
            }
            // The default scanner over the table top: a quarter of its rays
            // miss the scene, and the cloud lists them from the same apex.
            let no_return = msg.no_return.expect("a scan lists its empty rays");
            assert_eq!(no_return.apex, fov.apex);
            assert!(!no_return.cones.is_empty());
            stated.insert(msg.sequence, (fov, no_return));
        }
        surrogates_heard += 1;
        let (msg, _) = SurrogateMessage::from_bytes(&sample.payload().to_bytes()).unwrap();
        if let Some((fov, no_return)) = stated.get(&msg.source_sequence) {
            assert_eq!(msg.field_of_view.as_ref(), Some(fov));
            assert_eq!(msg.no_return.as_ref(), Some(no_return));
            matched += 1;
        }
    }
}
