//! The flood: bad messages of every topic kind on the keys the nodes listen
//! to, made from real messages of the running graph and sent in bursts, and
//! the account each node must give of them.

use crate::accounting::{settled, wait_delta, Delta};
use crate::bad_messages::bad_messages;
use crate::common::status_board::StatusBoard;
use crate::feeder;
use shroud_msg::{BlendCommandMessage, NodeStatusMessage, TopicKind};
use shroud_shapes::blend::BlendCommand;
use std::collections::HashMap;
use std::time::{Duration, Instant};
use zenoh::qos::CongestionControl;
use zenoh::Wait;

/// Of each topic kind: `N` garbage, `N` truncated and `N` wrong-version
/// messages on each key ...
pub const N: usize = 100;
/// ... that is, this many bad messages per key ...
pub const BAD: u64 = 3 * N as u64;
/// ... sent in this many bursts, 0.25 s apart.
const BURSTS: usize = 10;

pub struct Flood {
    /// Each key and its bad messages.
    pub keys: Vec<(String, Vec<Vec<u8>>)>,
}

impl Flood {
    /// Bad messages made from real ones: those the graph in `ns` publishes
    /// (heard on `session`), a valid cloud and a valid blend command. Every
    /// key a node listens to, and `cloud/junk`, which only the dashboard
    /// hears and nothing valid ever replaces there.
    pub fn of_graph(session: &zenoh::Session, ns: &str) -> Flood {
        let key = |kind: &str, name: &str| format!("shroud/{ns}/{kind}/{name}");
        let cloud = feeder::cloud(&crate::common::sheet(-2.0), 0);
        let paste = BlendCommand::Drop {
            at: glam::DVec3::ZERO,
            normal: None,
        };
        let command = BlendCommandMessage::new(1, 1, &paste).to_bytes().unwrap();
        let heard = |kind: TopicKind, name: &str| {
            let key = key(kind.as_str(), name);
            let real = crate::one_real(session, &key);
            (kind, key, real)
        };
        let real = [
            (TopicKind::Cloud, key("cloud", "s"), cloud.clone()),
            heard(TopicKind::Surrogate, "s"),
            heard(TopicKind::Joints, "demo_arm"),
            heard(TopicKind::Collision, "demo_arm"),
            heard(TopicKind::Status, "fit"),
            heard(TopicKind::Smooth, "s"),
            (TopicKind::Blend, key("blend", "blend"), command),
            (TopicKind::Cloud, key("cloud", "junk"), cloud),
        ];
        let keys = real
            .into_iter()
            .zip(1..)
            .map(|((kind, key, bytes), seed)| (key, bad_messages(kind, &bytes, N, seed)))
            .collect();
        Flood { keys }
    }

    pub fn messages(&self) -> usize {
        self.keys.iter().map(|(_, m)| m.len()).sum()
    }

    /// Sends the flood in bursts, each as fast as zenoh takes it, none lost
    /// (congestion control `Block`); the rate within the bursts (messages/s).
    pub fn send(&self, session: &zenoh::Session) -> f64 {
        let publishers: Vec<_> = self
            .keys
            .iter()
            .map(|(key, _)| {
                session
                    .declare_publisher(key.clone())
                    .congestion_control(CongestionControl::Block)
                    .wait()
                    .unwrap()
            })
            .collect();
        let indices: Vec<usize> = (0..3 * N).collect();
        let mut sending = Duration::ZERO;
        for burst in indices.chunks(3 * N / BURSTS) {
            let start = Instant::now();
            for &i in burst {
                for (publisher, (_, messages)) in publishers.iter().zip(&self.keys) {
                    publisher.put(messages[i].clone()).wait().unwrap();
                }
            }
            sending += start.elapsed();
            std::thread::sleep(Duration::from_millis(250));
        }
        self.messages() as f64 / sending.as_secs_f64()
    }
}

/// A fitter (`fit`, `smooth`: a mailbox that drops the oldest): each of the
/// `valid` clouds and of the [`BAD`] ones was taken or dropped with the
/// backlog, each taken one was used or counted malformed, once; no more bad
/// ones counted than sent, and no more clouds used than valid ones.
pub fn check_fitter(board: &StatusBoard, name: &str, before: &NodeStatusMessage, valid: u64) {
    let d = wait_delta(board, name, before, "every cloud taken or dropped", |d| {
        d.sum(&["received", "dropped_backlog"]) == valid + BAD
    });
    let used = d.sum(&["published", "publish_errors", "fit_errors"]);
    let (malformed, backlog) = (d.of("dropped_malformed"), d.of("dropped_backlog"));
    assert_eq!(used + malformed, d.of("received"), "{name}: {:?}", d.now);
    assert!(
        malformed <= BAD && BAD <= malformed + backlog,
        "{name}: {:?}",
        d.now
    );
    assert!(used <= valid, "{name} used {used} clouds of {valid} valid");
    eprintln!(
        "faults: {name}: received {}, dropped with the backlog {backlog}, malformed {malformed}, fitted {used} (of {valid} valid)",
        d.of("received")
    );
}

/// The blend node: every bad command taken (or dropped with the backlog) is
/// counted malformed, and none was applied.
pub fn check_blend(board: &StatusBoard, before: &NodeStatusMessage) {
    let d = wait_delta(board, "blend", before, "every command", |d| {
        d.sum(&["received", "dropped_backlog"]) == BAD
    });
    assert_eq!(d.of("dropped_malformed"), d.of("received"), "{:?}", d.now);
    assert_eq!(d.of("applied"), 0, "no bad command was applied");
    eprintln!(
        "faults: blend: received {}, dropped with the backlog {}, malformed {}, applied 0",
        d.of("received"),
        d.of("dropped_backlog"),
        d.of("dropped_malformed")
    );
}

/// Nodes that decode in zenoh's callback take every message: each bad one is
/// counted exactly once. The guard hears surrogates and joint states, the arm
/// verdicts, the launcher's summary statuses, surrogates and verdicts.
pub fn check_callback_nodes(board: &StatusBoard, before: &HashMap<String, NodeStatusMessage>) {
    let counted: Vec<String> = [("guard", 2), ("arm", 1), ("launcher", 3)]
        .into_iter()
        .map(|(node, keys)| {
            let d = wait_delta(board, node, &before[node], "each bad message", |d| {
                d.of("dropped_malformed") == keys * BAD
            });
            format!("{node} {} (of {})", d.of("dropped_malformed"), keys * BAD)
        })
        .collect();
    eprintln!("faults: counted malformed: {}", counted.join(", "));
}

/// The dashboard keeps the latest sample of each key: a bad one replaced
/// before its frame builder took it is never decoded (`samples_superseded`);
/// one replaced while it waits for its paced slot is not decoded either
/// (`paced_superseded`); every other one is counted malformed once. `sent`
/// bad messages reached it.
pub fn check_dashboard<'a>(
    board: &StatusBoard,
    before: &'a NodeStatusMessage,
    sent: u64,
) -> Delta<'a> {
    let now = settled(board, &["dashboard"]).remove("dashboard").unwrap();
    let d = Delta { before, now };
    let (malformed, superseded) = (d.of("dropped_malformed"), d.of("samples_superseded"));
    // Clouds, surfaces and smooth fits wait for their stream's paced slot;
    // one replaced while it waits is never decoded either.
    let paced = d.of("paced_superseded");
    assert!(malformed > 0 && malformed <= sent, "{:?}", d.now);
    assert!(malformed + superseded + paced >= sent, "{:?}", d.now);
    eprintln!(
        "faults: dashboard: {malformed} counted malformed, {superseded} samples and {paced} paced frames superseded unread (of {sent} bad)"
    );
    d
}
