//! What the test hears of the surrogates on a key, as they arrive: one value
//! taken from each (its latency, whether it is certified...) with its arrival
//! time, read over windows of time.

use shroud_msg::SurrogateMessage;
use shroud_surrogate::SurrogateWire;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use zenoh::Wait;

pub struct Heard<T> {
    seen: Arc<Mutex<Vec<(Instant, T)>>>,
    _subscriber: zenoh::pubsub::Subscriber<()>,
}

impl<T: Clone + Send + 'static> Heard<T> {
    /// Takes `value` of every surrogate on `key` (undecodable ones are skipped).
    pub fn watch(
        session: &zenoh::Session,
        key: String,
        value: impl Fn(&SurrogateMessage) -> T + Send + Sync + 'static,
    ) -> Heard<T> {
        let seen = Arc::new(Mutex::new(Vec::new()));
        let sink = seen.clone();
        let subscriber = session
            .declare_subscriber(key)
            .callback(move |s| {
                if let Ok((m, _)) = SurrogateMessage::from_bytes(&s.payload().to_bytes()) {
                    sink.lock().unwrap().push((Instant::now(), value(&m)));
                }
            })
            .wait()
            .unwrap();
        Heard {
            seen,
            _subscriber: subscriber,
        }
    }

    /// The values of the surrogates that arrived after `start`.
    pub fn since(&self, start: Instant) -> Vec<T> {
        let seen = self.seen.lock().unwrap();
        seen.iter()
            .filter(|(t, _)| *t > start)
            .map(|(_, v)| v.clone())
            .collect()
    }

    /// The values of the surrogates that arrive during the next `window`.
    pub fn over(&self, window: Duration) -> Vec<T> {
        let start = Instant::now();
        std::thread::sleep(window);
        self.since(start)
    }
}

/// The fit's latency as the guard ages a surrogate: its `pipeline_ns`, in ms.
pub fn latency_ms(m: &SurrogateMessage) -> f64 {
    m.pipeline_ns as f64 / 1e6
}

/// Every surface certified, over a non-empty cloud.
pub fn certified(m: &SurrogateMessage) -> bool {
    let checked = |c: &shroud_surrogate::Certificate| c.violations == 0 && c.points_checked > 0;
    m.surfaces.iter().all(|f| checked(&f.certificate))
}

pub fn median(values: &[f64]) -> f64 {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    sorted[sorted.len() / 2]
}
