//! The typed inputs and outputs on a real zenoh session (one peer with no
//! network: its own publications reach its own subscribers).

use super::{Arrival, NodeContext, NodeMetrics, OnMessage};
use shroud_graph::metrics::names as metric;
use shroud_msg::{JointStateMessage, MessageError, TopicKind, Topics};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use zenoh::Wait;

fn context() -> Arc<NodeContext> {
    let mut config = zenoh::Config::default();
    for (key, value) in [
        ("scouting/multicast/enabled", "false"),
        ("listen/endpoints", "[]"),
        (
            "timestamping/enabled",
            "{ router: true, peer: true, client: true }",
        ),
    ] {
        config.insert_json5(key, value).expect("a valid setting");
    }
    Arc::new(NodeContext {
        session: zenoh::open(config).wait().expect("a local session"),
        topics: Topics::new("runtime_test").expect("a valid namespace"),
        name: "test".into(),
        metrics: Arc::new(NodeMetrics::default()),
        stop: Arc::new(AtomicBool::new(false)),
        shm: false,
    })
}

fn joints(sequence: u64) -> JointStateMessage {
    JointStateMessage::new(1, sequence, "arm", vec!["j".into()], vec![0.25])
}

/// Waits until `done` holds, at most 10 s.
fn eventually(what: &str, done: impl Fn() -> bool) {
    let until = Instant::now() + Duration::from_secs(10);
    while !done() {
        assert!(Instant::now() < until, "timed out waiting for {what}");
        std::thread::sleep(Duration::from_millis(5));
    }
}

#[test]
fn a_queued_input_counts_what_it_receives_drops_and_refuses() {
    let ctx = context();
    let input = ctx.subscribe::<JointStateMessage>("a", 2).unwrap();
    let output = ctx.output::<JointStateMessage>("a").unwrap();
    let raw = ctx.publisher(TopicKind::Joints, "a").unwrap();
    for sequence in 0..3 {
        assert!(output.put(&joints(sequence)));
    }
    raw.put(b"not a message".to_vec()).wait().unwrap();
    let m = &ctx.metrics;
    assert_eq!(m.counter(metric::PUBLISHED), 3);
    // A queue of two keeps the newest two: the third joint state and the garbage.
    let mut used = Vec::new();
    while let Some(arrival) = input.recv_timeout(Duration::from_secs(5)) {
        assert!(arrival.published_ns.is_some(), "every sample is stamped");
        assert!(arrival.taken_ns >= arrival.received_ns);
        if let Some(sequence) = input.decoded(&arrival, |j| j.sequence) {
            used.push(sequence);
        }
        if m.counter(metric::RECEIVED) == 2 {
            break;
        }
    }
    assert_eq!(used, [2]);
    assert_eq!(m.counter(metric::DROPPED_MALFORMED), 1);
    input.recv_timeout(Duration::ZERO);
    assert_eq!(m.counter(metric::DROPPED_BACKLOG), 2);
    assert_eq!(m.counter(metric::RECEIVED), 2);
}

#[test]
fn an_input_stops_handing_over_once_the_node_stops() {
    let ctx = context();
    let input = ctx.subscribe::<JointStateMessage>("b", 4).unwrap();
    let output = ctx.output::<JointStateMessage>("b").unwrap();
    output.put(&joints(0));
    eventually("the sample", || ctx.metrics.counter(metric::PUBLISHED) == 1);
    ctx.stop.store(true, Ordering::Relaxed);
    assert!(input.recv_timeout(Duration::from_millis(50)).is_none());
    let mut calls = 0;
    input.for_each(|_, _| calls += 1);
    assert_eq!(calls, 0);
}

/// Records what it is handed, and refuses malformed payloads its own way.
#[derive(Default)]
struct Recorder {
    sequences: Mutex<Vec<u64>>,
    malformed: AtomicU64,
}

impl OnMessage<JointStateMessage> for Arc<Recorder> {
    fn on_message(&self, _: &Arrival, message: JointStateMessage) {
        self.sequences.lock().unwrap().push(message.sequence);
    }

    fn on_malformed(&self, _: &NodeMetrics, _: &Arrival, _: &MessageError) {
        self.malformed.fetch_add(1, Ordering::Relaxed);
    }
}

#[test]
fn a_listener_hands_over_decoded_messages_and_its_handler_judges_the_rest() {
    let ctx = context();
    let recorder = Arc::new(Recorder::default());
    let _listener = ctx
        .listen::<JointStateMessage>("c", recorder.clone())
        .unwrap();
    let counted = Arc::new(AtomicU64::new(0));
    let by_default = {
        let counted = counted.clone();
        ctx.listen::<JointStateMessage>("c", move |_: &Arrival, _: JointStateMessage| {
            counted.fetch_add(1, Ordering::Relaxed);
        })
        .unwrap()
    };
    assert_eq!(by_default.key(), "shroud/runtime_test/joints/c");
    let output = ctx.output::<JointStateMessage>("c").unwrap();
    let raw = ctx.publisher(TopicKind::Joints, "c").unwrap();
    output.put(&joints(7));
    raw.put(vec![0xc1]).wait().unwrap();
    output.put(&joints(8));
    eventually("both joint states", || {
        recorder.sequences.lock().unwrap().len() == 2 && counted.load(Ordering::Relaxed) == 2
    });
    assert_eq!(*recorder.sequences.lock().unwrap(), [7, 8]);
    assert_eq!(recorder.malformed.load(Ordering::Relaxed), 1);
    // The closure's listener counts the malformed payload as the runtime does.
    eventually("the malformed count", || {
        ctx.metrics.counter(metric::DROPPED_MALFORMED) == 1
    });
}

#[test]
fn an_output_counts_what_it_cannot_encode() {
    /// A message whose encoding fails.
    struct Unencodable;
    impl serde::Serialize for Unencodable {
        fn serialize<S: serde::Serializer>(&self, _: S) -> Result<S::Ok, S::Error> {
            Err(serde::ser::Error::custom("refused"))
        }
    }
    impl shroud_msg::WireOf<JointStateMessage> for Unencodable {}
    let ctx = context();
    let output = ctx.output::<JointStateMessage>("d").unwrap();
    assert!(!output.put(&Unencodable));
    assert_eq!(ctx.metrics.counter(metric::PUBLISH_ERRORS), 1);
    assert_eq!(ctx.metrics.counter(metric::PUBLISHED), 0);
}

#[test]
fn inputs_add_their_drops_to_the_one_backlog_count() {
    let ctx = context();
    let arrived = Arc::new(AtomicU64::new(0));
    let _witness = {
        let arrived = arrived.clone();
        ctx.listen_raw("shroud/runtime_test/joints/*", move |_| {
            arrived.fetch_add(1, Ordering::Relaxed);
        })
        .unwrap()
    };
    let inputs = ["e", "f"].map(|name| ctx.subscribe::<JointStateMessage>(name, 1).unwrap());
    for name in ["e", "f"] {
        let output = ctx.output::<JointStateMessage>(name).unwrap();
        (0..3).for_each(|sequence| assert!(output.put(&joints(sequence))));
    }
    eventually("every sample", || arrived.load(Ordering::Relaxed) == 6);
    // Each queue of one kept its newest and dropped two; the second input's
    // count adds to the first's instead of replacing it.
    for input in &inputs {
        assert!(input.recv_timeout(Duration::from_secs(5)).is_some());
    }
    drop(inputs);
    assert_eq!(ctx.metrics.counter(metric::DROPPED_BACKLOG), 4);
    assert_eq!(ctx.metrics.counter(metric::RECEIVED), 2);
}
