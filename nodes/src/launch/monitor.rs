//! The launcher's live summary: folds status, surrogate and collision messages
//! into a [`GraphSummary`] and prints its line every period.

use super::output;
use anyhow::Result;
use shroud_core::message::{
    CollisionMessage, NodeStatusMessage, SurrogateMessage, TopicKind, Topics,
};
use shroud_core::metrics::GraphSummary;
use std::collections::BTreeSet;
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

fn lock(m: &Mutex<GraphSummary>) -> MutexGuard<'_, GraphSummary> {
    m.lock().unwrap_or_else(|p| p.into_inner())
}

pub async fn run(session: zenoh::Session, topics: Result<Topics>, period: f64) {
    let Ok(topics) = topics else { return };
    let summary = Arc::new(Mutex::new(GraphSummary::default()));
    let mut subscribers = Vec::new();
    for kind in [
        TopicKind::Status,
        TopicKind::Surrogate,
        TopicKind::Collision,
    ] {
        let Ok(key) = topics.key(kind, "*") else {
            return;
        };
        let sink = summary.clone();
        let announced = Mutex::new(BTreeSet::new());
        let sub = session
            .declare_subscriber(&key)
            .callback(move |sample| {
                let bytes = sample.payload().to_bytes();
                let mut s = lock(&sink);
                // Malformed messages are the nodes' business (they count them);
                // the summary simply skips them.
                match kind {
                    TopicKind::Status => {
                        if let Ok(m) = NodeStatusMessage::from_bytes(&bytes) {
                            announce_url(
                                &m,
                                &mut announced.lock().unwrap_or_else(|p| p.into_inner()),
                            );
                            s.on_status(m);
                        }
                    }
                    TopicKind::Surrogate => {
                        if let Ok((m, _)) = SurrogateMessage::from_bytes(&bytes) {
                            s.on_surrogate(&m);
                        }
                    }
                    _ => {
                        if let Ok(m) = CollisionMessage::from_bytes(&bytes) {
                            s.on_collision(m);
                        }
                    }
                }
            })
            .await;
        match sub {
            Ok(sub) => subscribers.push(sub),
            Err(e) => {
                output::err(format!("[launch] summary unavailable: {e}"));
                return;
            }
        }
    }
    let start = Instant::now();
    let mut tick = tokio::time::interval(Duration::from_secs_f64(period));
    tick.tick().await;
    loop {
        tick.tick().await;
        let line = lock(&summary).line(start.elapsed().as_secs_f64());
        output::out(line);
    }
}

/// Prints a node's page once (`dashboard.url` in its status labels), so the
/// address is the first thing a user of the demo reads.
fn announce_url(status: &NodeStatusMessage, announced: &mut BTreeSet<String>) {
    if let Some(url) = status.labels.get("dashboard.url") {
        if announced.insert(format!("{}={url}", status.node)) {
            output::out(format!(
                "[launch] {}: open {url} in a browser (the live dashboard)",
                status.node
            ));
        }
    }
}
