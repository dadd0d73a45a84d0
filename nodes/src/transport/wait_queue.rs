//! The one blocking queue between zenoh's callbacks and a node's worker
//! thread: a backlog policy of the libraries (`DropOldest`, `LatestByKey`,
//! `ByteQueue`: what is kept when the worker falls behind) behind a lock,
//! with a wake-up for the worker and a close that wakes it for good.

use shroud_graph::backlog::{DropOldest, LatestByKey};
use shroud_record::ByteQueue;
use std::sync::{Condvar, Mutex, MutexGuard};
use std::time::Duration;

/// What the worker takes from a backlog policy.
pub trait Backlog {
    type Item;
    fn take(&mut self) -> Option<Self::Item>;
    fn is_empty(&self) -> bool;
}

impl<T> Backlog for DropOldest<T> {
    type Item = T;
    fn take(&mut self) -> Option<T> {
        self.pop()
    }
    fn is_empty(&self) -> bool {
        DropOldest::is_empty(self)
    }
}

impl<K: PartialEq, T> Backlog for LatestByKey<K, T> {
    type Item = (K, T);
    fn take(&mut self) -> Option<(K, T)> {
        LatestByKey::take(self)
    }
    fn is_empty(&self) -> bool {
        LatestByKey::is_empty(self)
    }
}

impl<T> Backlog for ByteQueue<T> {
    type Item = T;
    fn take(&mut self) -> Option<T> {
        self.pop()
    }
    fn is_empty(&self) -> bool {
        ByteQueue::is_empty(self)
    }
}

pub struct WaitQueue<B> {
    state: Mutex<State<B>>,
    ready: Condvar,
}

struct State<B> {
    backlog: B,
    closed: bool,
}

impl<B: Backlog> WaitQueue<B> {
    pub fn new(backlog: B) -> Self {
        Self {
            state: Mutex::new(State {
                backlog,
                closed: false,
            }),
            ready: Condvar::new(),
        }
    }

    fn lock(&self) -> MutexGuard<'_, State<B>> {
        // Every critical section is one push, take or read: a panic cannot
        // leave the backlog inconsistent, so poison is ignored.
        self.state.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// Runs `push` on the backlog and wakes the worker; `None` (and `push`
    /// not run) once the queue is closed.
    pub fn push<R>(&self, push: impl FnOnce(&mut B) -> R) -> Option<R> {
        let mut state = self.lock();
        if state.closed {
            return None;
        }
        let pushed = push(&mut state.backlog);
        drop(state);
        self.ready.notify_one();
        Some(pushed)
    }

    /// The backlog's next item, waiting up to `timeout`; `None` on timeout,
    /// or once closed and empty (what was queued before the close is still
    /// handed out).
    pub fn take(&self, timeout: Duration) -> Option<B::Item> {
        let state = self.lock();
        let (mut state, _) = self
            .ready
            .wait_timeout_while(state, timeout, |s| s.backlog.is_empty() && !s.closed)
            .unwrap_or_else(|p| p.into_inner());
        state.backlog.take()
    }

    /// Refuses further items and wakes every waiter.
    pub fn close(&self) {
        self.lock().closed = true;
        self.ready.notify_all();
    }

    pub fn is_closed(&self) -> bool {
        self.lock().closed
    }

    /// Closed and empty: nothing more will be handed out.
    pub fn is_drained(&self) -> bool {
        let state = self.lock();
        state.closed && state.backlog.is_empty()
    }

    /// Reads the backlog (its counts, its size).
    pub fn read<R>(&self, read: impl FnOnce(&B) -> R) -> R {
        read(&self.lock().backlog)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Arc;

    #[test]
    fn drop_oldest_keeps_the_newest_and_counts() {
        let q = WaitQueue::new(DropOldest::new(2));
        for i in 1..=3 {
            q.push(|b| b.push(i));
        }
        assert_eq!(q.read(|b| b.dropped()), 1);
        assert_eq!(q.take(Duration::ZERO), Some(2));
        assert_eq!(q.take(Duration::ZERO), Some(3));
        assert_eq!(q.take(Duration::from_millis(5)), None);
    }

    #[test]
    fn close_wakes_a_waiting_worker_and_refuses_more() {
        let q = Arc::new(WaitQueue::new(DropOldest::<u32>::new(1)));
        let waiter = {
            let q = q.clone();
            std::thread::spawn(move || q.take(Duration::from_secs(30)))
        };
        std::thread::sleep(Duration::from_millis(20));
        q.close();
        assert_eq!(waiter.join().unwrap(), None);
        assert_eq!(q.push(|b| b.push(7)), None);
        assert!(q.is_closed() && q.read(|b| b.is_empty()));
    }

    #[test]
    fn a_closed_queue_still_hands_out_what_it_holds() {
        let q = WaitQueue::new(ByteQueue::new(8));
        assert_eq!(q.push(|b| b.push(1, 8)), Some(Ok(())));
        assert_eq!(q.push(|b| b.push(2, 1)), Some(Err(2)));
        q.close();
        assert!(!q.is_drained());
        assert_eq!(q.take(Duration::from_secs(5)), Some(1));
        assert_eq!(q.take(Duration::from_secs(5)), None);
        assert!(q.is_drained());
    }

    #[test]
    fn latest_by_key_supersedes_per_key() {
        let q = WaitQueue::new(LatestByKey::default());
        q.push(|b| b.put("a", 1));
        q.push(|b| b.put("b", 2));
        q.push(|b| b.put("a", 3));
        assert_eq!(q.read(|b| b.superseded()), 1);
        assert_eq!(q.take(Duration::ZERO), Some(("a", 3)));
        assert_eq!(q.take(Duration::ZERO), Some(("b", 2)));
    }
}
