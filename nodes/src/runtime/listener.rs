//! A typed input used in zenoh's callback, for the messages a node must
//! answer at once (a joint state asks for a verdict) or fold into its state
//! as they come (a surrogate into the guard's views).

use super::arrival::{refused, Arrival};
use super::metrics::NodeMetrics;
use anyhow::Result;
use shroud_msg::{Message, MessageError};
use std::sync::Arc;
use zenoh::Wait;

/// What a node does with each message `M` of a listened topic.
pub trait OnMessage<M: Message>: Send + Sync + 'static {
    fn on_message(&self, arrival: &Arrival, message: M::View<'_>);

    /// A payload that does not decode: by default counted
    /// (`dropped_malformed`) and logged with its key. A node that must also
    /// react (a guard answers an undecodable joint state with a stop)
    /// overrides this.
    fn on_malformed(&self, metrics: &NodeMetrics, arrival: &Arrival, error: &MessageError) {
        metrics.drop_malformed(&arrival.key, error);
    }
}

impl<M, F> OnMessage<M> for F
where
    M: Message,
    F: Fn(&Arrival, M::View<'_>) + Send + Sync + 'static,
{
    fn on_message(&self, arrival: &Arrival, message: M::View<'_>) {
        self(arrival, message)
    }
}

/// Listens while it lives.
pub struct Listener {
    key: String,
    _subscriber: zenoh::pubsub::Subscriber<()>,
}

impl Listener {
    pub(super) fn new<M: Message>(
        session: &zenoh::Session,
        key: String,
        metrics: Arc<NodeMetrics>,
        handler: impl OnMessage<M>,
    ) -> Result<Self> {
        let subscriber = session
            .declare_subscriber(key.clone())
            .callback(move |sample| {
                if let Some(reason) = refused(&sample) {
                    return metrics.drop_malformed(sample.key_expr().as_str(), &reason);
                }
                let arrival = Arrival::of(&sample);
                let bytes = arrival.payload.to_bytes();
                match M::decode(&bytes) {
                    Ok(message) => handler.on_message(&arrival, message),
                    Err(e) => handler.on_malformed(&metrics, &arrival, &e),
                };
            })
            .wait()
            .map_err(|e| anyhow::anyhow!("subscribe {key}: {e}"))?;
        Ok(Self {
            key,
            _subscriber: subscriber,
        })
    }

    /// Every sample of the key expression `key` (wildcards allowed), handed
    /// as it came: for nodes that keep or forward payloads of many kinds
    /// (a recorder stores them, a viewer decodes them by kind).
    pub(super) fn raw(
        session: &zenoh::Session,
        key: String,
        handler: impl Fn(Arrival) + Send + Sync + 'static,
    ) -> Result<Self> {
        let subscriber = session
            .declare_subscriber(key.clone())
            .callback(move |sample| match refused(&sample) {
                Some(reason) => tracing::warn!(key = %sample.key_expr(), "dropped: {reason}"),
                None => handler(Arrival::of(&sample)),
            })
            .wait()
            .map_err(|e| anyhow::anyhow!("subscribe {key}: {e}"))?;
        Ok(Self {
            key,
            _subscriber: subscriber,
        })
    }

    /// The key expression listened to.
    pub fn key(&self) -> &str {
        &self.key
    }
}
