//! A viewer's subscriptions: every drawable or reported topic of the
//! namespace into its inbox, and the nodes' liveliness tokens.

use super::inbox::Inbox;
use crate::node::NodeContext;
use crate::runtime::Listener;
use anyhow::Result;
use shroud_msg::{TopicKey, TopicKind};
use std::sync::mpsc;
use std::sync::Arc;
use zenoh::sample::SampleKind;
use zenoh::Wait;

/// Clouds, surrogates, smooth fits, joint states, verdicts and status of the
/// whole namespace into `inbox`.
pub fn subscribe_drawables(ctx: &NodeContext, inbox: &Arc<Inbox>) -> Result<Vec<Listener>> {
    [
        TopicKind::Cloud,
        TopicKind::Surrogate,
        TopicKind::Smooth,
        TopicKind::Joints,
        TopicKind::Collision,
        TopicKind::Status,
    ]
    .into_iter()
    .map(|kind| {
        let key = ctx.key(kind, "*")?;
        let inbox = inbox.clone();
        ctx.listen_raw(&key, move |arrival| {
            inbox.push(&arrival.key, arrival.payload)
        })
    })
    .collect()
}

/// Liveliness tokens of the namespace's nodes, present ones first (history).
pub fn watch_tokens(
    ctx: &NodeContext,
    tokens: mpsc::Sender<(String, bool)>,
) -> Result<zenoh::pubsub::Subscriber<()>> {
    let key = ctx.key(TopicKind::Alive, "*")?;
    ctx.session
        .liveliness()
        .declare_subscriber(&key)
        .history(true)
        .callback(move |sample| {
            if let Some(topic) = TopicKey::parse(sample.key_expr().as_str()) {
                let _ = tokens.send((topic.name, sample.kind() == SampleKind::Put));
            }
        })
        .wait()
        .map_err(|e| anyhow::anyhow!("liveliness {key}: {e}"))
}
