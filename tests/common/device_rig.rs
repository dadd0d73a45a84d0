//! A test rig for real devices end to end: a zenoh hub the test owns, a
//! temp dir with the emulated device's stable link, and helpers that start
//! the emulator and the nodes and wait for what they publish.

use super::{hub_on_free_port, inbox, wiring, Inbox, Proc};
use shroud_msg::{CloudMessage, NodeStatusMessage, SurrogateMessage};
use shroud_surrogate::SurrogateWire;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

pub const LONG: Duration = Duration::from_secs(60);

/// A mount 2.5 m above the table top with the scan plane vertical, nodding
/// ±35° about y every 2 s (one sweep a second), as `launch/lidar.toml`.
pub const TILTING: [&str; 8] = [
    "--mount",
    "0,0,2.5,0,0,0",
    "--mount-axis",
    "y",
    "--sensor-offset",
    "0,0,0,0,90,0",
    "--sweep",
    "triangle:35:2",
];

pub struct Rig {
    pub endpoint: String,
    pub namespace: String,
    pub hub: zenoh::Session,
    pub dir: tempfile::TempDir,
}

impl Rig {
    pub fn new(namespace: &str) -> Rig {
        let (endpoint, hub) = hub_on_free_port();
        Rig {
            endpoint,
            namespace: namespace.to_owned(),
            hub,
            dir: tempfile::tempdir().expect("a temp dir"),
        }
    }

    pub fn link(&self) -> PathBuf {
        self.dir.path().join("device")
    }

    /// Starts the emulator of `model` behind the rig's link; waits until it is up.
    pub fn emulator(&self, model: &str, extra: &[&str]) -> Proc {
        let link = path(&self.link());
        let mut args = vec!["sensor-sim", "--device", model, "--link", &link];
        args.extend_from_slice(extra);
        let emulator = Proc::start(&args);
        emulator.expect_line(&format!("sensor-sim: {model} on"), LONG);
        emulator
    }

    /// Starts `shroud node <args...>` on the rig's hub.
    pub fn node(&self, args: &[&str]) -> Proc {
        let mut all = vec!["node"];
        all.extend_from_slice(args);
        all.extend(wiring(&self.endpoint, &self.namespace));
        Proc::start(&all)
    }

    /// The serial node for `device` on the rig's link, publishing `cloud/dev`.
    pub fn serial(&self, device: &str, extra: &[&str]) -> Proc {
        let link = path(&self.link());
        let mut args = vec![
            "serial",
            "--name",
            "dev",
            "--device",
            device,
            "--port",
            &link,
            "--stream",
            "dev",
            "--status-period",
            "0.2",
        ];
        args.extend_from_slice(extra);
        self.node(&args)
    }

    pub fn inbox(&self, kind: &str, name: &str) -> Inbox {
        inbox(
            &self.hub,
            format!("shroud/{}/{kind}/{name}", self.namespace),
        )
    }
}

pub fn path(p: &Path) -> String {
    p.to_str().expect("a UTF-8 temp path").to_owned()
}

/// The next `n` clouds on `inbox`; panics (with the node's output) if they
/// do not come in time.
pub fn clouds(inbox: &Inbox, n: usize, node: &Proc) -> Vec<CloudMessage> {
    let deadline = Instant::now() + LONG;
    let mut got = Vec::new();
    while got.len() < n {
        let left = deadline.saturating_duration_since(Instant::now());
        match inbox.recv_timeout(left.min(Duration::from_millis(200))) {
            Ok(Some(sample)) => {
                let cloud = CloudMessage::from_bytes(&sample.payload().to_bytes());
                got.push(cloud.expect("a valid cloud"));
            }
            _ if left.is_zero() => panic!(
                "{} of {n} clouds in {LONG:?}; node output:\n{}",
                got.len(),
                node.output()
            ),
            _ => {}
        }
    }
    got
}

/// The first status of the node that satisfies `done`.
pub fn status_until(
    inbox: &Inbox,
    node: &Proc,
    what: &str,
    done: impl Fn(&NodeStatusMessage) -> bool,
) -> NodeStatusMessage {
    let deadline = Instant::now() + LONG;
    let mut last = None;
    while Instant::now() < deadline {
        if let Ok(Some(sample)) = inbox.recv_timeout(Duration::from_millis(200)) {
            let status = NodeStatusMessage::from_bytes(&sample.payload().to_bytes());
            let status = status.expect("a valid status");
            if done(&status) {
                return status;
            }
            last = Some(status);
        }
    }
    panic!(
        "no status with {what} in {LONG:?}; last {last:?}; node output:\n{}",
        node.output()
    );
}

/// Starts a fit node on `cloud/dev` looking down.
pub fn fit_from_above(rig: &Rig) -> Proc {
    rig.node(&[
        "fit", "--input", "dev", "--grid", "12x12", "--side", "upper", "--dir", "0,0,-1",
    ])
}

/// Waits for a surrogate of one of the clouds seen (`seen` and those still
/// arriving) and checks it certifies every point of that cloud.
pub fn expect_certified_surrogate(
    cloud_inbox: &Inbox,
    surrogate_inbox: &Inbox,
    mut seen: Vec<CloudMessage>,
    node: &Proc,
) {
    let deadline = Instant::now() + LONG;
    loop {
        while let Ok(Some(sample)) = cloud_inbox.try_recv() {
            seen.push(CloudMessage::from_bytes(&sample.payload().to_bytes()).unwrap());
        }
        if let Ok(Some(sample)) = surrogate_inbox.recv_timeout(Duration::from_millis(200)) {
            let (msg, _) = SurrogateMessage::from_bytes(&sample.payload().to_bytes()).unwrap();
            if let Some(cloud) = seen.iter().find(|c| c.sequence == msg.source_sequence) {
                let points = cloud.point_array().unwrap().len() as u64;
                for surface in &msg.surfaces {
                    assert_eq!(surface.certificate.violations, 0);
                    assert_eq!(surface.certificate.points_checked, points);
                }
                return;
            }
        }
        assert!(
            Instant::now() < deadline,
            "no surrogate; node:\n{}",
            node.output()
        );
    }
}

pub fn label<'a>(status: &'a NodeStatusMessage, key: &str) -> &'a str {
    status.labels.get(key).map_or("", String::as_str)
}

/// Busy threads competing with the test's processes for the CPU for as long
/// as this lives: a loaded host, on which readings are read late.
pub struct CpuLoad {
    stop: std::sync::Arc<std::sync::atomic::AtomicBool>,
    threads: Vec<std::thread::JoinHandle<u64>>,
}

impl CpuLoad {
    /// `n` threads spinning until dropped.
    pub fn start(n: usize) -> CpuLoad {
        use std::sync::atomic::{AtomicBool, Ordering};
        let stop = std::sync::Arc::new(AtomicBool::new(false));
        let threads = (0..n)
            .map(|_| {
                let stop = stop.clone();
                std::thread::spawn(move || {
                    let mut spins = 0u64;
                    while !stop.load(Ordering::Relaxed) {
                        spins = std::hint::black_box(spins.wrapping_add(1));
                    }
                    spins
                })
            })
            .collect();
        CpuLoad { stop, threads }
    }
}

impl Drop for CpuLoad {
    fn drop(&mut self) {
        self.stop.store(true, std::sync::atomic::Ordering::Relaxed);
        for thread in self.threads.drain(..) {
            let _ = thread.join();
        }
    }
}
