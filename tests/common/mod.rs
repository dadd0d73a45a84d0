//! Shared helpers of the end-to-end graph tests: real `shroud` processes whose
//! output is collected line by line, a zenoh session the test owns, and process
//! liveness checks.
#![allow(dead_code)]

pub mod bench;
pub mod browser;
pub mod device_rig;
pub mod impair;
pub mod launched;
pub mod netns;
pub mod python;
pub mod status_board;
pub mod websocket;

use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc::{channel, Receiver};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use zenoh::Wait;

/// A running `shroud` process; killed (with its process group) when dropped.
pub struct Proc {
    pub child: Child,
    lines: Receiver<String>,
    pub seen: Arc<Mutex<Vec<String>>>,
}

impl Proc {
    pub fn start(args: &[&str]) -> Proc {
        Proc::spawn(Command::new(env!("CARGO_BIN_EXE_shroud")).args(args))
    }

    /// Starts `command` (another program than `shroud`, or with its own
    /// settings) and collects its output as [`Proc::start`] does.
    pub fn spawn(command: &mut Command) -> Proc {
        let mut child = command
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap_or_else(|e| panic!("{command:?} does not start: {e}"));
        let (tx, lines) = channel::<String>();
        let seen = Arc::new(Mutex::new(Vec::new()));
        for stream in [
            child
                .stdout
                .take()
                .map(|s| Box::new(s) as Box<dyn std::io::Read + Send>),
            child
                .stderr
                .take()
                .map(|s| Box::new(s) as Box<dyn std::io::Read + Send>),
        ]
        .into_iter()
        .flatten()
        {
            let (tx, seen) = (tx.clone(), seen.clone());
            std::thread::spawn(move || {
                for line in BufReader::new(stream).lines().map_while(Result::ok) {
                    seen.lock().unwrap().push(line.clone());
                    let _ = tx.send(line);
                }
            });
        }
        Proc { child, lines, seen }
    }

    pub fn pid(&self) -> i32 {
        self.child.id() as i32
    }

    /// Waits for a line containing `needle`; panics with the output so far if none.
    pub fn expect_line(&self, needle: &str, timeout: Duration) -> String {
        let deadline = Instant::now() + timeout;
        while let Some(left) = deadline.checked_duration_since(Instant::now()) {
            match self.lines.recv_timeout(left) {
                Ok(line) if line.contains(needle) => return line,
                Ok(_) => {}
                Err(_) => break,
            }
        }
        panic!(
            "no line containing {needle:?} within {timeout:?}; output:\n{}",
            self.output()
        );
    }

    /// After exit: waits (briefly) until the reader threads saw end of file, so
    /// that `output` holds everything the process wrote.
    fn drain_output(&self) {
        let deadline = Instant::now() + Duration::from_secs(5);
        while Instant::now() < deadline {
            if let Err(std::sync::mpsc::RecvTimeoutError::Disconnected) =
                self.lines.recv_timeout(Duration::from_millis(50))
            {
                return;
            }
        }
    }

    pub fn output(&self) -> String {
        self.seen.lock().unwrap().join("\n")
    }

    pub fn signal(&self, sig: i32) {
        unsafe {
            libc::kill(self.pid(), sig);
        }
    }

    /// Waits for exit; panics if it takes longer than `timeout`.
    pub fn wait_exit(&mut self, timeout: Duration) -> std::process::ExitStatus {
        let deadline = Instant::now() + timeout;
        loop {
            if let Some(status) = self.child.try_wait().expect("try_wait") {
                self.drain_output();
                return status;
            }
            assert!(
                Instant::now() < deadline,
                "process {} did not exit; output:\n{}",
                self.pid(),
                self.output()
            );
            std::thread::sleep(Duration::from_millis(20));
        }
    }
}

impl Drop for Proc {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// True while a process with this pid exists and is not a zombie.
pub fn alive(pid: i32) -> bool {
    match std::fs::read_to_string(format!("/proc/{pid}/stat")) {
        Ok(stat) => !stat
            .rsplit(')')
            .next()
            .is_some_and(|rest| rest.trim_start().starts_with('Z')),
        Err(_) => false,
    }
}

/// Waits until none of `pids` is alive.
pub fn assert_all_gone(pids: &[i32], timeout: Duration) {
    let deadline = Instant::now() + timeout;
    while pids.iter().any(|&p| alive(p)) {
        assert!(
            Instant::now() < deadline,
            "processes still alive: {:?}",
            pids.iter().filter(|&&p| alive(p)).collect::<Vec<_>>()
        );
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// A free TCP port on loopback (bound, then released for the test to use).
pub fn free_port() -> u16 {
    std::net::TcpListener::bind("127.0.0.1:0")
        .and_then(|l| l.local_addr())
        .map(|a| a.port())
        .expect("a free port")
}

/// A zenoh peer session for the test without multicast scouting, with these
/// further settings (JSON5 values by key).
pub fn peer_session(settings: &[(&str, String)]) -> zenoh::Session {
    open_peer(settings).expect("test session opens")
}

/// [`peer_session`], or why it could not open.
fn open_peer(settings: &[(&str, String)]) -> zenoh::Result<zenoh::Session> {
    let mut config = zenoh::Config::default();
    let base = [
        ("mode", "\"peer\"".to_string()),
        ("scouting/multicast/enabled", "false".to_string()),
    ];
    for (k, v) in base.iter().chain(settings) {
        config.insert_json5(k, v).expect("valid zenoh setting");
    }
    zenoh::open(config).wait()
}

/// A zenoh peer session for the test, listening on `endpoint`, without scouting.
pub fn hub(endpoint: &str) -> zenoh::Session {
    peer_session(&[("listen/endpoints", format!("[\"{endpoint}\"]"))])
}

/// A hub on a free loopback port, and that port's endpoint.
pub fn hub_on_free_port() -> (String, zenoh::Session) {
    // The port was free when asked, but another test binary running at the
    // same time may bind it first: then ask for another.
    let mut refused = Vec::new();
    for _ in 0..5 {
        let endpoint = format!("tcp/127.0.0.1:{}", free_port());
        match open_peer(&[("listen/endpoints", format!("[\"{endpoint}\"]"))]) {
            Ok(session) => return (endpoint, session),
            Err(e) => refused.push(format!("{endpoint}: {e}")),
        }
    }
    panic!("no loopback port for the test hub: {refused:?}")
}

/// A zenoh peer session for the test that connects to `endpoint`.
pub fn client_of(endpoint: &str) -> zenoh::Session {
    peer_session(&[
        ("connect/endpoints", format!("[\"{endpoint}\"]")),
        ("listen/endpoints", "[\"tcp/127.0.0.1:0\"]".to_string()),
    ])
}

/// The args that put a node on the test's hub.
pub fn wiring<'a>(endpoint: &'a str, namespace: &'a str) -> Vec<&'a str> {
    vec![
        "--connect",
        endpoint,
        "--multicast",
        "off",
        "--namespace",
        namespace,
    ]
}

/// Nanoseconds since the Unix epoch, as message stamps use.
pub fn unix_ns() -> u64 {
    std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_nanos() as u64)
        .unwrap_or(0)
}

/// A horizontal sheet of 40 x 40 points at height `z` over [-1, 1]^2 (a
/// little rough, so that it is not degenerate): far below the demo arm at
/// z = -2, across its path at z = 1.2.
pub fn sheet(z: f32) -> Vec<[f32; 3]> {
    (0..40 * 40)
        .map(|i| {
            [
                (i % 40) as f32 / 19.5 - 1.0,
                (i / 40) as f32 / 19.5 - 1.0,
                z + 0.01 * ((i * 7) % 5) as f32,
            ]
        })
        .collect()
}

/// OBJ bytes of the cube inscribed in the sphere of radius 0.7 around
/// (0.5, 0.5, 0.5): a coarse quad mesh of that ball, for parametric fits.
pub fn inscribed_cube_obj() -> Vec<u8> {
    let (vertices, faces) = shroud_shapes::mesh::cube_mesh().into_parts();
    let a = 0.7 / 3f64.sqrt();
    let scaled = vertices
        .iter()
        .map(|p| p.map(|x| 0.5 + (2.0 * x - 1.0) * a))
        .collect();
    let mesh = shroud_shapes::mesh::QuadMesh::new(scaled, faces).expect("a scaled cube");
    shroud_shapes::mesh::write_obj(&mesh)
}

/// Kills these pids (SIGKILL) when dropped, if still alive: a failed test must
/// not leave nodes behind, and a launcher's nodes are in their own process
/// groups, out of reach of the launcher's.
pub struct KillOnDrop(pub Vec<i32>);

impl Drop for KillOnDrop {
    fn drop(&mut self) {
        for &pid in self.0.iter().filter(|&&p| alive(p)) {
            unsafe {
                libc::kill(pid, libc::SIGKILL);
            }
        }
    }
}

/// A child process killed and reaped when dropped, for tests that handle its
/// pipes themselves.
pub struct Reaped(pub Child);

impl Reaped {
    /// Waits for exit; None if it takes longer than `timeout`.
    pub fn wait_timeout(&mut self, timeout: Duration) -> Option<std::process::ExitStatus> {
        let deadline = Instant::now() + timeout;
        while Instant::now() < deadline {
            if let Some(status) = self.0.try_wait().expect("try_wait") {
                return Some(status);
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        None
    }
}

impl Drop for Reaped {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// A subscriber with a FIFO of its samples.
pub type Inbox =
    zenoh::pubsub::Subscriber<zenoh::handlers::FifoChannelHandler<zenoh::sample::Sample>>;

/// Subscribes the test's session to `key`.
pub fn inbox(session: &zenoh::Session, key: String) -> Inbox {
    session
        .declare_subscriber(key)
        .wait()
        .expect("test subscriber")
}

/// Largest change between consecutive joint states seen over `window`.
pub fn joint_spread(joints: &Inbox, window: Duration) -> f64 {
    let spread = joint_spread_if_any(joints, window);
    assert!(spread.is_some(), "joint states keep coming");
    spread.unwrap_or_default()
}

/// [`joint_spread`], or `None` when fewer than three joint states came.
pub fn joint_spread_if_any(joints: &Inbox, window: Duration) -> Option<f64> {
    let _ = joints.drain().count();
    let start = Instant::now();
    let mut seen: Vec<Vec<f64>> = Vec::new();
    while start.elapsed() < window {
        if let Ok(Some(s)) = joints.recv_timeout(Duration::from_millis(20)) {
            let bytes = s.payload().to_bytes();
            let msg = shroud_msg::JointStateMessage::from_bytes(&bytes);
            seen.push(msg.expect("valid joint states").positions);
        }
    }
    let step = |w: &[Vec<f64>]| {
        w[0].iter()
            .zip(&w[1])
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
    };
    (seen.len() >= 3).then(|| seen.windows(2).map(step).fold(0.0, f64::max))
}

/// Points per source (parent, part, transition) of a blend node's model: its
/// intensity is each point's source code.
pub fn blend_sources(sample: &zenoh::sample::Sample) -> [usize; 3] {
    let msg = shroud_msg::CloudMessage::from_bytes(&sample.payload().to_bytes()).unwrap();
    let codes = msg
        .intensity_array()
        .unwrap()
        .expect("sources as intensity");
    assert_eq!(codes.len(), msg.point_array().unwrap().len());
    let mut count = [0; 3];
    for c in codes {
        count[c as usize] += 1;
    }
    count
}

/// Waits up to `timeout` for a blend model whose source counts satisfy
/// `wanted`; the counts, or the last ones seen.
pub fn wait_sources(
    models: &zenoh::pubsub::Subscriber<zenoh::handlers::FifoChannelHandler<zenoh::sample::Sample>>,
    timeout: Duration,
    wanted: impl Fn([usize; 3]) -> bool,
) -> Result<[usize; 3], Option<[usize; 3]>> {
    let deadline = Instant::now() + timeout;
    let mut last = None;
    while Instant::now() < deadline {
        if let Ok(Some(sample)) = models.recv_timeout(Duration::from_millis(500)) {
            let counts = blend_sources(&sample);
            if wanted(counts) {
                return Ok(counts);
            }
            last = Some(counts);
        }
    }
    Err(last)
}

/// Waits (up to `timeout`) until the arm moves: its deadman has a fresh clear.
pub fn wait_moving(joints: &Inbox, what: &str, procs: &[&Proc], timeout: Duration) {
    let deadline = Instant::now() + timeout;
    while joint_spread_if_any(joints, Duration::from_millis(300)).is_none_or(|s| s <= 1e-6) {
        assert!(
            Instant::now() < deadline,
            "{what}: the arm never moved; output:\n{}",
            procs
                .iter()
                .map(|p| p.output())
                .collect::<Vec<_>>()
                .join("\n---\n")
        );
    }
}
