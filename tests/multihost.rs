//! Hosts meeting at a `shroud router` over mutual TLS with the graph's
//! access control, on loopback: real `shroud certs` and `shroud router`
//! processes, and zenoh client sessions holding each host's certificate, a
//! stranger's, and none.

mod common;

use common::{free_port, Proc};
use std::path::Path;
use std::time::{Duration, Instant};
use zenoh::Wait;

/// A sensor host and an arm host around a router host (`tls` paths are
/// filled in with the test's directory).
const CELL: &str = r#"
namespace = "cell"
[hosts.hub]
router = true
listen = ["tls/127.0.0.1:PORT"]
tls = { root_ca = "DIR/ca.pem", certificate = "DIR/hub.pem", private_key = "DIR/hub.key" }
[hosts.sensor]
connect = ["tls/127.0.0.1:PORT"]
tls = { root_ca = "DIR/ca.pem", certificate = "DIR/sensor.pem", private_key = "DIR/sensor.key" }
[hosts.arm]
connect = ["tls/127.0.0.1:PORT"]
tls = { root_ca = "DIR/ca.pem", certificate = "DIR/arm.pem", private_key = "DIR/arm.key" }

[[node]]
name = "scanner"
kind = "scanner"
host = "sensor"
outputs = { cloud = "table" }

[[node]]
name = "fit"
kind = "fit"
host = "sensor"
inputs = { cloud = "table" }
outputs = { surrogate = "table" }

[[node]]
name = "guard"
kind = "guard"
host = "arm"
inputs = { surrogate = "table", joints = "ur" }
outputs = { collision = "ur" }

[[node]]
name = "arm"
kind = "arm"
host = "arm"
inputs = { collision = "ur" }
outputs = { joints = "ur" }
"#;

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
    let graph = dir.path().join("cell.toml");
    let text = CELL
        .replace("PORT", &port.to_string())
        .replace("DIR", &dir.path().display().to_string());
    std::fs::write(&graph, text).unwrap();
    let graph = graph.display().to_string();
    let out = dir.path().display().to_string();

    // The authority and every host's certificate, and a stranger's signed
    // by the same authority.
    let certs = |args: &[&str]| {
        let mut all = vec!["certs", "--out", &out];
        all.extend(args);
        let done = std::process::Command::new(env!("CARGO_BIN_EXE_shroud"))
            .args(&all)
            .output()
            .unwrap();
        assert!(
            done.status.success(),
            "{}",
            String::from_utf8_lossy(&done.stderr)
        );
    };
    certs(&["--graph", &graph]);
    certs(&["--host", "intruder", "--host", "observer"]);

    let router = Proc::start(&[
        "--log", "info", "router", "--graph", &graph, "--host", "hub",
    ]);
    router.expect_line("listening on", Duration::from_secs(20));

    let observer = client(dir.path(), &endpoint, Some("observer")).expect("observer connects");
    let seen = observer
        .declare_subscriber("shroud/cell/**")
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
        (&arm, "shroud/cell/collision/ur", "arm"),
        (&arm, "shroud/cell/joints/ur", "arm"),
        (&sensor, "shroud/cell/surrogate/table", "sensor"),
        (&sensor, "shroud/cell/surrogate/table.s2", "sensor"),
        (&sensor, "shroud/cell/collision/ur", "forged"),
        (&sensor, "shroud/cell/joints/ur", "forged"),
        (&arm, "shroud/cell/surrogate/table", "forged"),
        (&intruder, "shroud/cell/collision/ur", "forged"),
        (&intruder, "shroud/cell/surrogate/table", "forged"),
        (&intruder, "shroud/cell/status/guard", "forged"),
    ];
    let mut received = std::collections::BTreeSet::new();
    let mut router_status = false;
    let deadline = Instant::now() + Duration::from_secs(5);
    while Instant::now() < deadline {
        for (session, key, who) in &puts {
            session.put(*key, *who).wait().unwrap();
        }
        std::thread::sleep(Duration::from_millis(50));
        while let Ok(Some(sample)) = seen.try_recv() {
            let key = sample.key_expr().to_string();
            if key == "shroud/cell/status/router.hub" {
                router_status = true;
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
    assert!(router_status, "the router's status is on the bus");
}

/// `launch/hosts.toml` on loopback: the router host, then each host's
/// launcher with `--host`; the arm host's guard judges surrogates fitted on
/// the sensor host, two hops away, and its verdicts reach the router.
#[test]
fn the_demo_runs_across_hosts_through_the_router() {
    let dir = tempfile::tempdir().unwrap();
    let port = free_port();
    let endpoint = format!("tls/127.0.0.1:{port}");
    let root = env!("CARGO_MANIFEST_DIR");
    let text = std::fs::read_to_string(format!("{root}/launch/hosts.toml"))
        .unwrap()
        .replace("127.0.0.1:7450", &format!("127.0.0.1:{port}"))
        .replace("\"certs/", &format!("\"{}/", dir.path().display()))
        .replace("\"launch/", &format!("\"{root}/launch/"));
    let graph = dir.path().join("hosts.toml");
    std::fs::write(&graph, text).unwrap();
    let graph = graph.display().to_string();
    let out = dir.path().display().to_string();
    let done = std::process::Command::new(env!("CARGO_BIN_EXE_shroud"))
        .args([
            "certs", "--graph", &graph, "--out", &out, "--host", "observer",
        ])
        .output()
        .unwrap();
    assert!(
        done.status.success(),
        "{}",
        String::from_utf8_lossy(&done.stderr)
    );

    let router = Proc::start(&[
        "--log", "info", "router", "--graph", &graph, "--host", "hub",
    ]);
    router.expect_line("listening on", Duration::from_secs(20));
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
            return;
        }
        last = Some(format!("{:?}: {}", msg.verdict, msg.reason));
    }
    panic!(
        "no verdict on a surrogate from the sensor host (last: {last:?})\nsensor:\n{}\narm:\n{}",
        sensor.output(),
        arm.output()
    );
}
