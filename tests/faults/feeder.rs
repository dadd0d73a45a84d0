//! The test as the graph's sensor: valid clouds (the sheet far below the
//! demo arm) at 10 Hz on one stream, published so that none is lost on the way
//! (congestion control `Block`), pausable, and counted: the flood test must
//! know exactly how many valid clouds each node was sent.

use shroud_msg::{CloudMessage, SensorPose};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Arc;
use std::time::Duration;
use zenoh::qos::CongestionControl;
use zenoh::Wait;

const PERIOD: Duration = Duration::from_millis(100);

pub struct Feeder {
    feeding: Arc<AtomicBool>,
    sent: Arc<AtomicU64>,
    stop: Arc<AtomicBool>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Feeder {
    /// Starts feeding `key` at once.
    pub fn start(session: &zenoh::Session, key: String) -> Feeder {
        let publisher = session
            .declare_publisher(key)
            .congestion_control(CongestionControl::Block)
            .wait()
            .expect("the feeder's publisher");
        let (feeding, sent, stop) = (
            Arc::new(AtomicBool::new(true)),
            Arc::new(AtomicU64::new(0)),
            Arc::new(AtomicBool::new(false)),
        );
        let (f, s, st) = (feeding.clone(), sent.clone(), stop.clone());
        let points = super::common::sheet(-2.0);
        let thread = std::thread::spawn(move || {
            while !st.load(Ordering::Relaxed) {
                if f.load(Ordering::Relaxed) {
                    let sequence = s.load(Ordering::Relaxed);
                    publisher
                        .put(cloud(&points, sequence))
                        .wait()
                        .expect("a valid cloud is sent");
                    s.fetch_add(1, Ordering::Relaxed);
                }
                std::thread::sleep(PERIOD);
            }
        });
        Feeder {
            feeding,
            sent,
            stop,
            thread: Some(thread),
        }
    }

    /// Stops sending (the cloud being sent, if any, goes out first: call
    /// [`Self::sent`] after a period to count it).
    pub fn pause(&self) {
        self.feeding.store(false, Ordering::Relaxed);
        std::thread::sleep(PERIOD * 2);
    }

    pub fn resume(&self) {
        self.feeding.store(true, Ordering::Relaxed);
    }

    /// Valid clouds sent so far; their sequences are `0..sent`.
    pub fn sent(&self) -> u64 {
        self.sent.load(Ordering::Relaxed)
    }
}

/// A valid cloud of `points`, as a sensor node would send it.
pub fn cloud(points: &[[f32; 3]], sequence: u64) -> Vec<u8> {
    let stamp = super::common::unix_ns();
    CloudMessage::new(stamp, sequence, "feeder", SensorPose::default(), points)
        .to_bytes()
        .expect("a cloud encodes")
}

impl Drop for Feeder {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}
