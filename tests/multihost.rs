//! Hosts meeting at a `shroud router` over mutual TLS with the graph's
//! access control, on loopback: real `shroud certs` and `shroud router`
//! processes, and zenoh client sessions holding each host's certificate, a
//! stranger's, and none.

mod common;

use common::{free_port, Proc};
use shroud_msg::NodeStatusMessage;
use std::path::Path;
use std::time::{Duration, Instant};
use zenoh::Wait;

/// `launch/hosts.toml` for this test: its router on `port`, its
/// certificates in `dir` (written there by `shroud certs`, with an
/// `observer` and an `intruder` that own no stream), its files found from
/// anywhere. Returns the graph file's path.
fn hosts_graph(dir: &Path, port: u16) -> String {
    let root = env!("CARGO_MANIFEST_DIR");
    let text = std::fs::read_to_string(format!("{root}/launch/hosts.toml"))
        .unwrap()
        .replace("127.0.0.1:7450", &format!("127.0.0.1:{port}"))
        .replace("\"certs/", &format!("\"{}/", dir.display()))
        .replace("\"launch/", &format!("\"{root}/launch/"));
    let graph = dir.join("hosts.toml");
    std::fs::write(&graph, text).unwrap();
    let graph = graph.display().to_string();
    let out = dir.display().to_string();
    let args = [
        "certs", "--graph", &graph, "--out", &out, "--host", "observer", "--host", "intruder",
    ];
    let done = std::process::Command::new(env!("CARGO_BIN_EXE_shroud"))
        .args(args)
        .output()
        .unwrap();
    assert!(
        done.status.success(),
        "{}",
        String::from_utf8_lossy(&done.stderr)
    );
    graph
}

/// `shroud router` for the graph's router host, once it listens.
fn router(graph: &str) -> Proc {
    let router = Proc::start(&["--log", "info", "router", "--graph", graph, "--host", "hub"]);
    router.expect_line("listening on", Duration::from_secs(20));
    router
}

/// A client of the router at `endpoint` holding `identity`'s certificate
/// from `dir` (None: only trusting the authority, presenting none).
fn client(dir: &Path, endpoint: &str, identity: Option<&str>) -> zenoh::Result<zenoh::Session> {
    let mut config = zenoh::Config::default();
    let path = |file: String| format!("{:?}", dir.join(file).display().to_string());
    let mut settings = vec![
        ("mode", "\"client\"".to_string()),
        ("connect/endpoints", format!("[\"{endpoint}\"]")),
        ("scouting/multicast/enabled", "false".into()),
        (
            "transport/link/tls/root_ca_certificate",
            path("ca.pem".into()),
        ),
    ];
    if let Some(name) = identity {
        settings.extend([
            (
                "transport/link/tls/connect_certificate",
                path(format!("{name}.pem")),
            ),
            (
                "transport/link/tls/connect_private_key",
                path(format!("{name}.key")),
            ),
            ("transport/link/tls/enable_mtls", "true".into()),
        ]);
    }
    for (key, value) in settings {
        config
            .insert_json5(key, &value)
            .expect("valid zenoh setting");
    }
    zenoh::open(config).wait()
}

#[test]
fn the_router_lets_each_host_publish_only_its_own_streams() {
    let dir = tempfile::tempdir().unwrap();
    let port = free_port();
    let endpoint = format!("tls/127.0.0.1:{port}");
    let graph = hosts_graph(dir.path(), port);
    let router = router(&graph);

    let observer = client(dir.path(), &endpoint, Some("observer")).expect("observer connects");
    let seen = observer
        .declare_subscriber("shroud/demo/**")
        .wait()
        .unwrap();
    let arm = client(dir.path(), &endpoint, Some("arm")).expect("arm connects");
    let sensor = client(dir.path(), &endpoint, Some("sensor")).expect("sensor connects");
    let intruder = client(dir.path(), &endpoint, Some("intruder")).expect("intruder connects");
    assert!(
        client(dir.path(), &endpoint, None).is_err(),
        "a client without a certificate is refused by mutual TLS"
    );

    let puts = [
        (&arm, "shroud/demo/collision/demo_arm", "arm"),
        (&arm, "shroud/demo/joints/demo_arm", "arm"),
        (&sensor, "shroud/demo/surrogate/spheres", "sensor"),
        // The fit node has no `sectors`: its host owns no sector stream.
        (&sensor, "shroud/demo/surrogate/spheres.s2", "forged"),
        (&sensor, "shroud/demo/collision/demo_arm", "forged"),
        (&sensor, "shroud/demo/joints/demo_arm", "forged"),
        (&arm, "shroud/demo/surrogate/spheres", "forged"),
        (&intruder, "shroud/demo/collision/demo_arm", "forged"),
        (&intruder, "shroud/demo/surrogate/spheres", "forged"),
        (&intruder, "shroud/demo/status/guard", "forged"),
        // Wildcard keys reach every subscriber they intersect: no host may
        // put on one.
        (&sensor, "shroud/demo/collision/*", "forged"),
        (&arm, "shroud/demo/surrogate/**", "forged"),
        (&intruder, "shroud/demo/**", "forged"),
    ];
    let mut received = std::collections::BTreeSet::new();
    let forged_per_round = puts.iter().filter(|(_, _, who)| *who == "forged").count() as u64;
    let mut rounds = 0;
    let deadline = Instant::now() + Duration::from_secs(5);
    while Instant::now() < deadline {
        for (session, key, who) in &puts {
            session.put(*key, *who).wait().unwrap();
        }
        rounds += 1;
        std::thread::sleep(Duration::from_millis(50));
        while let Ok(Some(sample)) = seen.try_recv() {
            let key = sample.key_expr().to_string();
            if key.starts_with("shroud/demo/status/router") {
                continue;
            }
            let who = String::from_utf8_lossy(&sample.payload().to_bytes()).into_owned();
            received.insert((key, who));
        }
    }
    let expected: std::collections::BTreeSet<(String, String)> = puts
        .iter()
        .filter(|(_, _, who)| *who != "forged")
        .map(|(_, key, who)| (key.to_string(), who.to_string()))
        .collect();
    assert_eq!(received, expected, "router output:\n{}", router.output());
    // Every forged message was refused at the router, and counted in its
    // status: zenoh's put returned Ok to the forger.
    let statuses = observer
        .declare_subscriber("shroud/demo/status/router.hub")
        .wait()
        .unwrap();
    let refused = forged_per_round * rounds;
    let deadline = Instant::now() + Duration::from_secs(10);
    let mut counted = None;
    while Instant::now() < deadline && counted != Some(refused) {
        if let Ok(Some(sample)) = statuses.recv_timeout(Duration::from_millis(500)) {
            let status = NodeStatusMessage::from_bytes(&sample.payload().to_bytes()).unwrap();
            counted = Some(status.counter("zenoh_dropped_access_control"));
        }
    }
    assert_eq!(
        counted,
        Some(refused),
        "refused messages counted in the router's status"
    );
}

/// `launch/hosts.toml` on loopback: the router host, then each host's
/// launcher with `--host`; the arm host's guard judges surrogates fitted on
/// the sensor host, two hops away, and its verdicts reach the router.
#[test]
fn the_demo_runs_across_hosts_through_the_router() {
    let dir = tempfile::tempdir().unwrap();
    let port = free_port();
    let endpoint = format!("tls/127.0.0.1:{port}");
    let graph = hosts_graph(dir.path(), port);
    let _router = router(&graph);
    let sensor = Proc::start(&["launch", &graph, "--host", "sensor"]);
    let arm = Proc::start(&["launch", &graph, "--host", "arm"]);
    let observer = client(dir.path(), &endpoint, Some("observer")).expect("observer connects");
    let verdicts = observer
        .declare_subscriber("shroud/demo/collision/demo_arm")
        .wait()
        .unwrap();
    let deadline = Instant::now() + Duration::from_secs(60);
    let mut last = None;
    while Instant::now() < deadline {
        let Ok(Some(sample)) = verdicts.recv_timeout(Duration::from_millis(500)) else {
            continue;
        };
        let msg = shroud_msg::CollisionMessage::from_bytes(&sample.payload().to_bytes()).unwrap();
        if msg.views > 0 && msg.surrogate_sequence > 0 {
            return node_list_shows_every_host(dir.path(), &endpoint);
        }
        last = Some(format!("{:?}: {}", msg.verdict, msg.reason));
    }
    panic!(
        "no verdict on a surrogate from the sensor host (last: {last:?})\nsensor:\n{}\narm:\n{}",
        sensor.output(),
        arm.output()
    );
}

/// `shroud node list` through the router, as the docs show it, lists the
/// nodes of every host and the router.
fn node_list_shows_every_host(dir: &Path, endpoint: &str) {
    let file = |name: &str| dir.join(name).display().to_string();
    let listed = std::process::Command::new(env!("CARGO_BIN_EXE_shroud"))
        .args([
            "node",
            "list",
            "--namespace",
            "demo",
            "--mode",
            "client",
            "--connect",
            endpoint,
        ])
        .args([
            "--tls-root-ca",
            &file("ca.pem"),
            "--tls-certificate",
            &file("observer.pem"),
        ])
        .args(["--tls-private-key", &file("observer.key")])
        .output()
        .unwrap();
    let out = String::from_utf8_lossy(&listed.stdout);
    assert!(
        listed.status.success(),
        "{}",
        String::from_utf8_lossy(&listed.stderr)
    );
    for node in ["scanner", "fit", "guard", "arm", "router.hub"] {
        assert!(
            out.lines().any(|l| l.starts_with(node)),
            "{node} not listed:\n{out}"
        );
    }
}
