//! Pacing per key: at most one item of each key per period, the latest one.
//! A viewer bridge that forwards a 30 Hz cloud stream to a client whose queue
//! counts messages (not bytes) bounds what a key can put in that queue per
//! second; an item that comes too soon waits, replacing an older waiting one
//! (counted superseded), and leaves once its key's period has passed. Plain
//! data: time is an argument.

use std::collections::BTreeMap;

/// See the module documentation.
#[derive(Debug, Clone)]
pub struct Paced<K, T> {
    period_ns: u64,
    /// When each key last let an item through.
    passed: BTreeMap<K, u64>,
    waiting: BTreeMap<K, T>,
    superseded: u64,
}

impl<K: Ord + Clone, T> Paced<K, T> {
    /// Lets one item of a key through per `period_ns` (0: every item).
    pub fn new(period_ns: u64) -> Self {
        Self {
            period_ns,
            passed: BTreeMap::new(),
            waiting: BTreeMap::new(),
            superseded: 0,
        }
    }

    fn due(&self, key: &K, now_ns: u64) -> bool {
        self.passed
            .get(key)
            .is_none_or(|&at| now_ns.saturating_sub(at) >= self.period_ns)
    }

    /// `item` if its key may pass at `now_ns` (it then waits a period);
    /// otherwise it waits in place of the key's waiting item.
    pub fn offer(&mut self, key: K, item: T, now_ns: u64) -> Option<T> {
        if self.due(&key, now_ns) {
            // A waiting item can only be older than this one.
            if self.waiting.remove(&key).is_some() {
                self.superseded += 1;
            }
            self.passed.insert(key, now_ns);
            return Some(item);
        }
        if self.waiting.insert(key, item).is_some() {
            self.superseded += 1;
        }
        None
    }

    /// The waiting items whose keys may pass at `now_ns`, in key order.
    pub fn release(&mut self, now_ns: u64) -> Vec<(K, T)> {
        let keys: Vec<K> = self
            .waiting
            .keys()
            .filter(|k| self.due(k, now_ns))
            .cloned()
            .collect();
        keys.into_iter()
            .filter_map(|k| {
                let item = self.waiting.remove(&k)?;
                self.passed.insert(k.clone(), now_ns);
                Some((k, item))
            })
            .collect()
    }

    /// Items replaced while waiting, since creation.
    pub fn superseded(&self) -> u64 {
        self.superseded
    }

    /// Items waiting now (at most one per key).
    pub fn waiting(&self) -> usize {
        self.waiting.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_item_per_key_per_period_and_the_latest_waits() {
        let mut paced = Paced::new(100);
        assert_eq!(paced.offer("cloud", 1, 0), Some(1));
        assert_eq!(paced.offer("verdict", 10, 5), Some(10));
        assert_eq!(paced.offer("cloud", 2, 30), None);
        assert_eq!(paced.offer("cloud", 3, 60), None);
        assert_eq!((paced.waiting(), paced.superseded()), (1, 1));
        assert!(paced.release(99).is_empty());
        assert_eq!(paced.release(100), vec![("cloud", 3)]);
        assert!(paced.release(150).is_empty());
        // Released at 100: the next may pass at 200.
        assert_eq!(paced.offer("cloud", 4, 150), None);
        assert_eq!(paced.offer("cloud", 5, 200), Some(5));
        // The waiting 4 was overtaken by 5: superseded, not left behind.
        assert!(paced.release(1000).is_empty());
        assert_eq!((paced.waiting(), paced.superseded()), (0, 2));
    }

    /// Whatever the offers: per key, items pass at least a period apart, and
    /// every item offered passed, waits, or is counted superseded.
    #[test]
    fn passes_are_a_period_apart_and_every_item_is_accounted_for() {
        let mut x = 0x9E37_79B9_u32;
        let mut next = move || {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            x
        };
        let mut paced = Paced::new(50);
        let mut last: BTreeMap<u32, u64> = BTreeMap::new();
        let (mut now, mut passed) = (0u64, 0u64);
        let offered = 5000;
        for _ in 0..offered {
            now += u64::from(next() % 20);
            let key = next() % 4;
            let mut out = paced.release(now);
            out.extend(paced.offer(key, (), now).map(|item| (key, item)));
            for (k, ()) in out {
                if let Some(&at) = last.get(&k) {
                    assert!(now - at >= 50, "key {k} passed twice within a period");
                }
                last.insert(k, now);
                passed += 1;
            }
        }
        assert!(passed > 0 && paced.superseded() > 0);
        assert_eq!(
            passed + paced.waiting() as u64 + paced.superseded(),
            offered
        );
    }
}
