//! The browsers connected to the dashboard, each with one pending frame per
//! (type, stream) (`shroud-graph`'s [`LatestByKey`]): the frame builder never waits for a
//! browser, and a slow browser skips frames of a stream instead of queueing
//! them (counted as superseded).

use shroud_graph::backlog::LatestByKey;
use std::collections::BTreeSet;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};
use tokio::sync::Notify;

/// An encoded frame, shared by every browser that gets it.
pub type SharedFrame = Arc<Vec<u8>>;

fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    // Each critical section is one slot operation: nothing to leave half done.
    m.lock().unwrap_or_else(|p| p.into_inner())
}

/// One connected browser.
pub struct Browser {
    slots: Mutex<LatestByKey<String, SharedFrame>>,
    wake: Notify,
    /// Points per cloud this browser asked for.
    budget: AtomicUsize,
    closed: AtomicBool,
}

impl Browser {
    /// The next frame to send, waiting until there is one; `None` once closed.
    pub async fn next_frame(&self) -> Option<(String, SharedFrame)> {
        loop {
            if self.closed.load(Ordering::Relaxed) {
                return None;
            }
            if let Some(item) = lock(&self.slots).take() {
                return Some(item);
            }
            self.wake.notified().await;
        }
    }

    pub fn set_budget(&self, budget: usize) {
        self.budget.store(budget, Ordering::Relaxed);
    }

    pub fn budget(&self) -> usize {
        self.budget.load(Ordering::Relaxed)
    }

    /// Queues `frame` under `key`, replacing an unsent one of the same key.
    pub fn put(&self, key: &str, frame: SharedFrame) -> bool {
        let replaced = lock(&self.slots).put(key.to_string(), frame);
        self.wake.notify_one();
        replaced
    }

    fn close(&self) {
        self.closed.store(true, Ordering::Relaxed);
        self.wake.notify_one();
    }
}

/// Every connected browser, and what the dashboard sent them.
#[derive(Default)]
pub struct Hub {
    browsers: Mutex<Vec<Arc<Browser>>>,
    pub frames_sent: AtomicU64,
    pub frames_superseded: AtomicU64,
    /// Set when a browser joined: the frame builder then resends the latest of
    /// everything (a new browser must not wait for the next change).
    joined: AtomicBool,
}

impl Hub {
    /// A new browser with this point budget.
    pub fn join(&self, budget: usize) -> Arc<Browser> {
        let browser = Arc::new(Browser {
            slots: Mutex::new(LatestByKey::default()),
            wake: Notify::new(),
            budget: AtomicUsize::new(budget),
            closed: AtomicBool::new(false),
        });
        lock(&self.browsers).push(browser.clone());
        self.joined.store(true, Ordering::Relaxed);
        browser
    }

    pub fn leave(&self, browser: &Arc<Browser>) {
        browser.close();
        lock(&self.browsers).retain(|b| !Arc::ptr_eq(b, browser));
    }

    /// Closes every browser's queue (the node is stopping).
    pub fn close_all(&self) {
        for b in lock(&self.browsers).drain(..) {
            b.close();
        }
    }

    pub fn count(&self) -> usize {
        lock(&self.browsers).len()
    }

    /// True once after a browser joined.
    pub fn take_joined(&self) -> bool {
        self.joined.swap(false, Ordering::Relaxed)
    }

    /// The distinct point budgets of the connected browsers.
    pub fn budgets(&self) -> BTreeSet<usize> {
        lock(&self.browsers).iter().map(|b| b.budget()).collect()
    }

    /// Gives `frame` to every browser.
    pub fn broadcast(&self, key: &str, frame: Vec<u8>) {
        let frame = Arc::new(frame);
        for b in lock(&self.browsers).iter() {
            self.count_put(b.put(key, frame.clone()));
        }
    }

    /// Gives `frame` to the browsers whose budget is `budget`.
    pub fn broadcast_to_budget(&self, key: &str, budget: usize, frame: Vec<u8>) {
        let frame = Arc::new(frame);
        for b in lock(&self.browsers).iter().filter(|b| b.budget() == budget) {
            self.count_put(b.put(key, frame.clone()));
        }
    }

    fn count_put(&self, replaced: bool) {
        if replaced {
            self.frames_superseded.fetch_add(1, Ordering::Relaxed);
        }
    }
}
