//! A bounded queue between a zenoh callback and a worker thread, with `shroud-graph`'s
//! drop-oldest backlog policy ([`DropOldest`]): a lock, a condition variable
//! to wake the worker, and a close that wakes it for good.

use shroud_graph::backlog::DropOldest;
use std::sync::{Condvar, Mutex, MutexGuard};
use std::time::Duration;

pub struct Mailbox<T> {
    queue: Mutex<State<T>>,
    ready: Condvar,
}

struct State<T> {
    items: DropOldest<T>,
    closed: bool,
}

impl<T> Mailbox<T> {
    pub fn new(capacity: usize) -> Self {
        Self {
            queue: Mutex::new(State {
                items: DropOldest::new(capacity),
                closed: false,
            }),
            ready: Condvar::new(),
        }
    }

    fn lock(&self) -> MutexGuard<'_, State<T>> {
        // A panic while holding this lock cannot leave the queue inconsistent
        // (every critical section is a single push/pop), so poison is ignored.
        self.queue.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// Adds an item; returns how many old items were dropped to make room.
    pub fn push(&self, item: T) -> u64 {
        let mut state = self.lock();
        if state.closed {
            return 0;
        }
        let dropped = state.items.push(item);
        drop(state);
        self.ready.notify_one();
        dropped
    }

    /// The oldest queued item, waiting up to `timeout`; `None` on timeout or close.
    pub fn pop(&self, timeout: Duration) -> Option<T> {
        let state = self.lock();
        let (mut state, _) = self
            .ready
            .wait_timeout_while(state, timeout, |s| s.items.is_empty() && !s.closed)
            .unwrap_or_else(|p| p.into_inner());
        state.items.pop()
    }

    /// Wakes every waiter and refuses further items.
    pub fn close(&self) {
        self.lock().closed = true;
        self.ready.notify_all();
    }

    pub fn is_closed(&self) -> bool {
        self.lock().closed
    }

    /// Items dropped because the worker fell behind, since creation.
    pub fn dropped(&self) -> u64 {
        self.lock().items.dropped()
    }

    pub fn len(&self) -> usize {
        self.lock().items.len()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Arc;

    #[test]
    fn drops_the_oldest_and_counts() {
        let m = Mailbox::new(2);
        assert_eq!(m.push(1), 0);
        assert_eq!(m.push(2), 0);
        assert_eq!(m.push(3), 1);
        assert_eq!(m.dropped(), 1);
        assert_eq!(m.pop(Duration::ZERO), Some(2));
        assert_eq!(m.pop(Duration::ZERO), Some(3));
        assert_eq!(m.pop(Duration::from_millis(5)), None);
    }

    #[test]
    fn close_wakes_a_waiting_worker() {
        let m = Arc::new(Mailbox::<u32>::new(1));
        let waiter = {
            let m = m.clone();
            std::thread::spawn(move || m.pop(Duration::from_secs(30)))
        };
        std::thread::sleep(Duration::from_millis(20));
        m.close();
        assert_eq!(waiter.join().unwrap(), None);
        assert_eq!(m.push(7), 0);
        assert!(m.is_empty() && m.is_closed());
    }
}
