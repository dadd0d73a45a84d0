//! The launcher's live summary: folds status, surrogate and collision messages
//! into a [`GraphSummary`] and prints its line every period. Messages it cannot
//! decode are skipped and counted in the launcher's status.

use super::output;
use super::roster::Roster;
use anyhow::Result;
use shroud_graph::metrics::GraphSummary;
use shroud_msg::{
    CollisionMessage, MessageError, NodeStatusMessage, SurrogateMessage, TopicKind, Topics,
};
use shroud_surrogate::SurrogateWire;
use std::collections::BTreeSet;
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

fn lock(m: &Mutex<GraphSummary>) -> MutexGuard<'_, GraphSummary> {
    m.lock().unwrap_or_else(|p| p.into_inner())
}

pub async fn run(session: zenoh::Session, topics: Result<Topics>, period: f64, roster: Roster) {
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
        let roster = roster.clone();
        let sub = session
            .declare_subscriber(&key)
            .callback(move |sample| {
                let bytes = sample.payload().to_bytes();
                // Malformed messages are the nodes' business (they log them);
                // the summary skips them and counts them once, unlogged.
                if fold(kind, &bytes, &mut lock(&sink), &announced).is_err() {
                    roster.malformed();
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

/// Folds one message of `kind` into the summary.
fn fold(
    kind: TopicKind,
    bytes: &[u8],
    summary: &mut GraphSummary,
    announced: &Mutex<BTreeSet<String>>,
) -> Result<(), MessageError> {
    match kind {
        TopicKind::Status => {
            let m = NodeStatusMessage::from_bytes(bytes)?;
            announce_url(&m, &mut announced.lock().unwrap_or_else(|p| p.into_inner()));
            summary.on_status(m);
        }
        TopicKind::Surrogate => summary.on_surrogate(&SurrogateMessage::from_bytes(bytes)?.0),
        _ => summary.on_collision(CollisionMessage::from_bytes(bytes)?),
    }
    Ok(())
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
