//! The recorder's queue between zenoh's callbacks and the writer thread:
//! `shroud-record`'s byte-bounded drop-newest [`ByteQueue`] behind a lock, with a wake-up
//! for the writer and a close that wakes it for good.

use shroud_record::ByteQueue;
use std::sync::{Condvar, Mutex, MutexGuard};
use std::time::Duration;

pub struct WriteQueue<T> {
    state: Mutex<State<T>>,
    ready: Condvar,
}

struct State<T> {
    items: ByteQueue<T>,
    closed: bool,
}

impl<T> WriteQueue<T> {
    pub fn new(capacity_bytes: usize) -> Self {
        Self {
            state: Mutex::new(State {
                items: ByteQueue::new(capacity_bytes),
                closed: false,
            }),
            ready: Condvar::new(),
        }
    }

    fn lock(&self) -> MutexGuard<'_, State<T>> {
        // Every critical section is one push or pop: a panic cannot leave the
        // queue inconsistent, so poison is ignored.
        self.state.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// Queues `item` of `len` bytes; hands it back when the queue is full or
    /// closed.
    pub fn push(&self, item: T, len: usize) -> Result<(), T> {
        let mut state = self.lock();
        if state.closed {
            return Err(item);
        }
        state.items.push(item, len)?;
        drop(state);
        self.ready.notify_one();
        Ok(())
    }

    /// The oldest item, waiting up to `timeout`; `None` on timeout, or once
    /// closed and empty.
    pub fn pop(&self, timeout: Duration) -> Option<T> {
        let state = self.lock();
        let (mut state, _) = self
            .ready
            .wait_timeout_while(state, timeout, |s| s.items.is_empty() && !s.closed)
            .unwrap_or_else(|p| p.into_inner());
        state.items.pop()
    }

    /// Refuses further items and wakes the writer; queued items stay to be
    /// drained.
    pub fn close(&self) {
        self.lock().closed = true;
        self.ready.notify_all();
    }

    pub fn is_closed_and_empty(&self) -> bool {
        let state = self.lock();
        state.closed && state.items.is_empty()
    }

    pub fn bytes(&self) -> usize {
        self.lock().items.bytes()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn full_or_closed_hands_the_item_back_and_drains_after_close() {
        let q = WriteQueue::new(8);
        assert!(q.push(1, 8).is_ok());
        assert_eq!(q.push(2, 1), Err(2));
        q.close();
        assert_eq!(q.push(3, 0), Err(3));
        assert!(!q.is_closed_and_empty());
        assert_eq!(q.pop(Duration::ZERO), Some(1));
        assert_eq!(q.pop(Duration::from_secs(5)), None);
        assert!(q.is_closed_and_empty());
    }
}
