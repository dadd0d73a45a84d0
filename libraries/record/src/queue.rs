//! The recorder's queue between its subscribers and its writer thread: bounded
//! by bytes, and when full it drops the NEWEST message (the one that does not
//! fit), unlike the fitter's drop-oldest mailbox: a recording keeps a
//! contiguous past rather than a gappy one, and what was accepted is written.
//! Plain data; the node wraps it with a lock and a wake-up.

use std::collections::VecDeque;

#[derive(Debug)]
pub struct ByteQueue<T> {
    items: VecDeque<(T, usize)>,
    bytes: usize,
    capacity_bytes: usize,
}

impl<T> ByteQueue<T> {
    pub fn new(capacity_bytes: usize) -> Self {
        Self {
            items: VecDeque::new(),
            bytes: 0,
            capacity_bytes,
        }
    }

    /// Queues `item` of `len` bytes, or hands it back when it does not fit.
    /// An item larger than the whole capacity is taken when the queue is
    /// empty (else it could never be recorded).
    pub fn push(&mut self, item: T, len: usize) -> Result<(), T> {
        let fits = self.bytes.saturating_add(len) <= self.capacity_bytes;
        if !fits && !self.items.is_empty() {
            return Err(item);
        }
        self.bytes = self.bytes.saturating_add(len);
        self.items.push_back((item, len));
        Ok(())
    }

    pub fn pop(&mut self) -> Option<T> {
        let (item, len) = self.items.pop_front()?;
        self.bytes -= len;
        Some(item)
    }

    pub fn bytes(&self) -> usize {
        self.bytes
    }

    pub fn len(&self) -> usize {
        self.items.len()
    }

    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn drops_the_newest_when_full_and_frees_bytes_on_pop() {
        let mut q = ByteQueue::new(10);
        assert!(q.push('a', 6).is_ok());
        assert_eq!(q.push('b', 5), Err('b'));
        assert!(q.push('c', 4).is_ok());
        assert_eq!(q.bytes(), 10);
        assert_eq!(q.pop(), Some('a'));
        assert!(q.push('d', 6).is_ok());
        assert_eq!((q.pop(), q.pop(), q.pop()), (Some('c'), Some('d'), None));
        assert_eq!(q.bytes(), 0);
    }

    #[test]
    fn an_oversized_item_passes_alone() {
        let mut q = ByteQueue::new(10);
        assert!(q.push(1, 50).is_ok());
        assert_eq!(q.push(2, 1), Err(2));
        assert_eq!(q.pop(), Some(1));
        assert!(q.is_empty());
    }
}
