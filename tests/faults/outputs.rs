//! What the nodes publish while they are flooded, checked as it arrives (in
//! zenoh's callbacks: the test must never slow the graph down by reading
//! late): no surrogate or smooth fit of a bad cloud, and every bad joint state
//! answered with a stop. Payloads that do not decode are the flood itself (the
//! test hears its own messages) and are skipped.

use super::bad_messages::BAD_SEQUENCES;
use shroud_msg::{CollisionMessage, SmoothPatchesMessage, SurrogateMessage};
use shroud_surrogate::SurrogateWire;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use zenoh::Wait;

#[derive(Default)]
pub struct Counts {
    pub surrogates: AtomicU64,
    pub smooth_fits: AtomicU64,
    /// Verdicts for joint states that could not be decoded (sequence `u64::MAX`).
    pub undecodable_joints_answered: AtomicU64,
    /// What must never happen, described.
    pub violations: Mutex<Vec<String>>,
}

impl Counts {
    fn violation(&self, what: String) {
        self.violations
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .push(what);
    }

    pub fn get(counter: &AtomicU64) -> u64 {
        counter.load(Ordering::Relaxed)
    }

    /// Each of `bad` undecodable joint states was answered with a stop, once,
    /// and nothing came of a bad message.
    pub fn check(&self, bad: u64) {
        let answered = &self.undecodable_joints_answered;
        assert!(
            crate::wait_until(|| Self::get(answered) >= bad),
            "{} of {bad} bad joint states answered",
            Self::get(answered)
        );
        assert_eq!(Self::get(answered), bad, "each bad joint state once");
        let violations = self.violations.lock().unwrap();
        assert!(violations.is_empty(), "{violations:#?}");
    }
}

/// What a subscriber checks of each payload it hears.
type Check = Box<dyn Fn(&Counts, &[u8]) + Send + Sync>;

pub struct Outputs {
    pub counts: Arc<Counts>,
    _subscribers: Vec<zenoh::pubsub::Subscriber<()>>,
}

impl Outputs {
    /// Watches `surrogate/<stream>`, `smooth/<stream>` and `collision/<arm>`.
    pub fn watch(session: &zenoh::Session, ns: &str, stream: &str, arm: &str) -> Outputs {
        let counts = Arc::new(Counts::default());
        let subscribe = |key: String, check: Check| {
            let counts = counts.clone();
            session
                .declare_subscriber(key)
                .callback(move |s| check(&counts, &s.payload().to_bytes()))
                .wait()
                .expect("an output subscriber")
        };
        let subscribers = vec![
            subscribe(
                format!("shroud/{ns}/surrogate/{stream}"),
                Box::new(|c, bytes| {
                    if let Ok((m, _)) = SurrogateMessage::from_bytes(bytes) {
                        c.surrogates.fetch_add(1, Ordering::Relaxed);
                        if m.source_sequence >= BAD_SEQUENCES {
                            c.violation(format!("a surrogate of bad cloud {}", m.source_sequence));
                        }
                    }
                }),
            ),
            subscribe(
                format!("shroud/{ns}/smooth/{stream}"),
                Box::new(|c, bytes| {
                    if let Ok(m) = SmoothPatchesMessage::from_bytes(bytes) {
                        c.smooth_fits.fetch_add(1, Ordering::Relaxed);
                        if m.source_sequence >= BAD_SEQUENCES {
                            c.violation(format!("a smooth fit of bad cloud {}", m.source_sequence));
                        }
                    }
                }),
            ),
            subscribe(
                format!("shroud/{ns}/collision/{arm}"),
                Box::new(|c, bytes| {
                    if let Ok(m) = CollisionMessage::from_bytes(bytes) {
                        check_verdict(c, &m);
                    }
                }),
            ),
        ];
        Outputs {
            counts,
            _subscribers: subscribers,
        }
    }
}

/// A verdict for a bad joint state must be a stop, and only an undecodable
/// one (its sequence unknown) can be answered: a wrong-version joint state's
/// own sequence must never come back.
fn check_verdict(c: &Counts, m: &CollisionMessage) {
    if m.joints_sequence == u64::MAX {
        c.undecodable_joints_answered
            .fetch_add(1, Ordering::Relaxed);
        if !m.stop {
            c.violation(format!("an undecodable joint state was cleared: {m:?}"));
        }
    } else if m.joints_sequence >= BAD_SEQUENCES {
        c.violation(format!(
            "bad joint state {} was decoded and answered {}",
            m.joints_sequence,
            m.verdict.name()
        ));
    }
}
