//! End-to-end test of the `blend` node (paper 001): a scanner publishes the
//! parent scene, the node blends a simulated part where `shroud blend-cmd`
//! drops it, and republishes the model with each point's source as intensity.

mod common;

use common::{assert_all_gone, free_port, hub, wait_sources, wiring, Proc};
use shroud_msg::{BlendCommandMessage, NodeStatusMessage};
use shroud_shapes::blend::BlendCommand;
use std::time::{Duration, Instant};
use zenoh::Wait;

const LONG: Duration = Duration::from_secs(90);

/// Waits (within `LONG`) for a model whose source counts satisfy `wanted`: the
/// node also republishes its unchanged model every second.
fn wait_model(
    models: &zenoh::pubsub::Subscriber<zenoh::handlers::FifoChannelHandler<zenoh::sample::Sample>>,
    what: &str,
    node: &Proc,
    wanted: impl Fn([usize; 3]) -> bool,
) -> [usize; 3] {
    wait_sources(models, LONG, wanted).unwrap_or_else(|last| {
        panic!(
            "no model as wanted after {what} (last {last:?}); node:\n{}",
            node.output()
        )
    })
}

#[test]
fn blend_node_follows_drops_and_clears_and_survives_garbage() {
    let endpoint = format!("tcp/127.0.0.1:{}", free_port());
    let session = hub(&endpoint);
    let ns = "e2e-blend";
    let models = session
        .declare_subscriber(format!("shroud/{ns}/cloud/blend"))
        .wait()
        .unwrap();
    let statuses = session
        .declare_subscriber(format!("shroud/{ns}/status/blend"))
        .wait()
        .unwrap();
    let w = wiring(&endpoint, ns);
    let mut node = Proc::start(
        &[
            &[
                "node",
                "blend",
                "--parent-stream",
                "table",
                "--child-part",
                "hemisphere",
                "--part-size",
                "0.3",
                "--centres",
                "400",
            ][..],
            &w,
        ]
        .concat(),
    );
    let mut scanner = Proc::start(
        &[
            &[
                "node",
                "scanner",
                "--scene",
                "table-top",
                "--points",
                "20000",
                "--rate",
                "2",
                "--stream",
                "table",
                "--time-scale",
                "0",
            ][..],
            &w,
        ]
        .concat(),
    );

    // The parent alone first.
    wait_model(&models, "start", &node, |c| {
        c[0] > 10_000 && c[1] == 0 && c[2] == 0
    });

    // A drop: the part and a transition surface appear.
    let drop = |at: &str| {
        let mut cmd = Proc::start(&[&["blend-cmd"][..], &w, &["drop", "--at", at]].concat());
        assert!(cmd.wait_exit(LONG).success(), "{}", cmd.output());
    };
    drop("-0.3,-1.1,0");
    wait_model(&models, "the drop", &node, |c| c[1] > 500 && c[2] > 100);

    // Garbage and invalid commands are counted; the node keeps working.
    let key = format!("shroud/{ns}/blend/blend");
    let mut nan = BlendCommandMessage::new(
        1,
        1,
        &BlendCommand::Drop {
            at: glam::DVec3::ZERO,
            normal: None,
        },
    );
    nan.at = Some([f64::NAN, 0.0, 0.0]);
    for payload in [b"garbage".to_vec(), Vec::new(), nan.to_bytes().unwrap()] {
        session.put(&key, payload).wait().unwrap();
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
            if status.counter("dropped_malformed") >= 3 {
                break;
            }
        }
    }

    // A drag of several drops ends where the last one put the part; a clear
    // leaves the parent alone.
    let mut drag = Proc::start(
        &[
            &["blend-cmd"][..],
            &w,
            &[
                "drag",
                "--from",
                "-0.3,-1.1,0",
                "--to",
                "0.3,-1.1,0",
                "--steps",
                "4",
                "--rate",
                "20",
            ],
        ]
        .concat(),
    );
    assert!(drag.wait_exit(LONG).success(), "{}", drag.output());
    let mut clear = Proc::start(&[&["blend-cmd"][..], &w, &["clear"]].concat());
    assert!(clear.wait_exit(LONG).success(), "{}", clear.output());
    wait_model(&models, "the clear", &node, |c| c[1] == 0 && c[2] == 0);

    let pids = [node.pid(), scanner.pid()];
    node.signal(libc::SIGTERM);
    scanner.signal(libc::SIGTERM);
    assert!(node.wait_exit(LONG).success(), "{}", node.output());
    assert!(scanner.wait_exit(LONG).success(), "{}", scanner.output());
    assert!(!node.output().contains("panicked"), "{}", node.output());
    assert_all_gone(&pids, Duration::from_secs(5));
}
