//! Backlog policies between a producer and a slower consumer, each bounded and
//! counting what it drops: [`DropOldest`], a queue that drops the OLDEST item
//! when full (a fitter that falls behind works on the freshest cloud instead of
//! building an unbounded backlog), and [`LatestByKey`], one slot per key where
//! a new item supersedes the unsent one (a viewer that falls behind skips
//! frames of a stream, never another stream's). Plain data; the nodes wrap them
//! with a lock and a wake-up.

use std::collections::VecDeque;

/// One pending item per key: a new item for a key replaces the unsent one
/// (counted as superseded); items leave in the order their keys first became
/// pending, so a busy stream cannot starve a quiet one.
#[derive(Debug, Clone)]
pub struct LatestByKey<K, T> {
    pending: VecDeque<(K, T)>,
    superseded: u64,
}

impl<K: PartialEq, T> Default for LatestByKey<K, T> {
    fn default() -> Self {
        Self {
            pending: VecDeque::new(),
            superseded: 0,
        }
    }
}

impl<K: PartialEq, T> LatestByKey<K, T> {
    /// Sets `key`'s pending item; true if it replaced an unsent one.
    pub fn put(&mut self, key: K, item: T) -> bool {
        if let Some(slot) = self.pending.iter_mut().find(|(k, _)| *k == key) {
            slot.1 = item;
            self.superseded += 1;
            true
        } else {
            self.pending.push_back((key, item));
            false
        }
    }

    /// The pending item that has waited longest.
    pub fn take(&mut self) -> Option<(K, T)> {
        self.pending.pop_front()
    }

    /// Items replaced before they were taken, since creation.
    pub fn superseded(&self) -> u64 {
        self.superseded
    }

    pub fn len(&self) -> usize {
        self.pending.len()
    }

    pub fn is_empty(&self) -> bool {
        self.pending.is_empty()
    }
}

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
    fn latest_by_key_keeps_one_item_per_key_in_first_pending_order() {
        let mut slots = LatestByKey::default();
        assert!(!slots.put("cloud/a", 1));
        assert!(!slots.put("verdict", 10));
        assert!(slots.put("cloud/a", 2));
        assert!(slots.put("cloud/a", 3));
        assert_eq!(slots.len(), 2);
        assert_eq!(slots.superseded(), 2);
        assert_eq!(slots.take(), Some(("cloud/a", 3)));
        assert_eq!(slots.take(), Some(("verdict", 10)));
        assert_eq!(slots.take(), None);
        assert!(slots.is_empty());
    }

    /// Whatever the puts and takes: at most one item per key, every put
    /// either taken (the newest of its key), pending, or counted superseded.
    #[test]
    fn latest_by_key_accounts_for_every_item() {
        let mut x = 0x2545_F491_u32;
        let mut next = move || {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            x
        };
        let mut slots = LatestByKey::default();
        let (mut put, mut taken) = (0u64, 0u64);
        let mut newest = [0u32; 4];
        for step in 0..5000u32 {
            if next() % 3 == 0 {
                if let Some((key, value)) = slots.take() {
                    assert_eq!(value, newest[key], "a taken item is its key's newest");
                    taken += 1;
                }
            } else {
                let key = (next() % 4) as usize;
                newest[key] = step;
                slots.put(key, step);
                put += 1;
            }
            assert!(slots.len() <= 4);
            assert_eq!(put, taken + slots.len() as u64 + slots.superseded());
        }
    }

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
