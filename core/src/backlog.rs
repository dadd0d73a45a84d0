//! The backlog policy between a subscriber and its worker: a bounded queue that
//! drops the OLDEST item when full and counts every drop, so a fitter that
//! falls behind works on the freshest cloud instead of building an unbounded
//! backlog. Plain data; the nodes wrap it with a lock and a condition variable.

use std::collections::VecDeque;

/// See the module documentation.
#[derive(Debug, Clone)]
pub struct DropOldest<T> {
    items: VecDeque<T>,
    capacity: usize,
    dropped: u64,
}

impl<T> DropOldest<T> {
    /// A queue of at most `capacity` items (at least one).
    pub fn new(capacity: usize) -> Self {
        Self {
            items: VecDeque::new(),
            capacity: capacity.max(1),
            dropped: 0,
        }
    }

    /// Adds an item; returns how many old items were dropped to make room.
    pub fn push(&mut self, item: T) -> u64 {
        let mut dropped = 0;
        while self.items.len() >= self.capacity {
            self.items.pop_front();
            dropped += 1;
        }
        self.items.push_back(item);
        self.dropped += dropped;
        dropped
    }

    /// The oldest item.
    pub fn pop(&mut self) -> Option<T> {
        self.items.pop_front()
    }

    /// Items dropped since creation.
    pub fn dropped(&self) -> u64 {
        self.dropped
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
    fn drops_the_oldest_and_counts() {
        let mut q = DropOldest::new(2);
        assert_eq!(q.push(1), 0);
        assert_eq!(q.push(2), 0);
        assert_eq!(q.push(3), 1);
        assert_eq!((q.dropped(), q.len()), (1, 2));
        assert_eq!(q.pop(), Some(2));
        assert_eq!(q.pop(), Some(3));
        assert_eq!(q.pop(), None);
        assert!(q.is_empty());
    }

    /// Whatever the pushes and pops, the queue holds the newest items in
    /// order, never more than its capacity, and every item is either popped,
    /// still queued or counted as dropped.
    #[test]
    fn keeps_the_newest_and_accounts_for_every_item() {
        for capacity in 0..5 {
            let mut q = DropOldest::new(capacity);
            let (mut pushed, mut popped) = (0u64, 0u64);
            let mut last_popped = None;
            for step in 0..500u64 {
                if (step * 2_654_435_761) % 7 < 4 {
                    q.push(pushed);
                    pushed += 1;
                } else if let Some(v) = q.pop() {
                    assert!(last_popped.is_none_or(|l| v > l), "in order");
                    last_popped = Some(v);
                    popped += 1;
                }
                assert!(q.len() <= capacity.max(1));
                assert_eq!(popped + q.len() as u64 + q.dropped(), pushed);
            }
        }
    }
}
