//! A typed output: messages `M` published on `shroud/<ns>/<M::KIND>/<name>`
//! with the kind's quality of service, through shared memory when the node
//! gave it a pool and runs with `--shm on`, each publication counted
//! (`published`, `publish_errors`, and `sent_shm`/`sent_copy` with a pool).

use super::metrics::NodeMetrics;
use crate::transport::{topic_publisher, PayloadWriter};
use anyhow::Result;
use shroud_graph::metrics::names as metric;
use shroud_msg::{Message, WireOf};
use std::marker::PhantomData;
use std::sync::Arc;
use zenoh::time::Timestamp;
use zenoh::Wait;

pub struct Output<M: Message> {
    publisher: zenoh::pubsub::Publisher<'static>,
    key: String,
    writer: PayloadWriter,
    /// Whether the node asked for a shared-memory pool (its counts are then
    /// part of its status).
    pooled: bool,
    metrics: Arc<NodeMetrics>,
    _message: PhantomData<fn(&M)>,
}

impl<M: Message> Output<M> {
    /// `writer` with a pool (`pooled`) or without.
    pub(super) fn new(
        session: &zenoh::Session,
        key: String,
        writer: PayloadWriter,
        pooled: bool,
        metrics: Arc<NodeMetrics>,
    ) -> Result<Self> {
        let publisher = topic_publisher(session, key.clone(), M::KIND)?;
        Ok(Self {
            publisher,
            key,
            writer,
            pooled,
            metrics,
            _message: PhantomData,
        })
    }

    /// The key expression published on.
    pub fn key(&self) -> &str {
        &self.key
    }

    /// The zenoh publisher (to wait for subscribers, or to take a timestamp).
    pub fn publisher(&self) -> &zenoh::pubsub::Publisher<'static> {
        &self.publisher
    }

    /// Whether large messages go through shared memory.
    pub fn uses_shm(&self) -> bool {
        self.writer.uses_shm()
    }

    /// Publishes `message`; whether it was handed to zenoh. A message that
    /// cannot be encoded or is refused is logged and counted
    /// (`publish_errors`).
    pub fn put(&self, message: &impl WireOf<M>) -> bool {
        self.send(message, None)
    }

    /// [`Self::put`] with the publication's timestamp taken by the caller
    /// (before its last step, so that what follows counts as transit).
    pub fn put_stamped(&self, message: &impl WireOf<M>, timestamp: Timestamp) -> bool {
        self.send(message, Some(timestamp))
    }

    fn send(&self, message: &impl WireOf<M>, timestamp: Option<Timestamp>) -> bool {
        let sent = self
            .writer
            .encode(message)
            .map_err(|e| format!("encode: {e}"))
            .and_then(|payload| {
                let put = self.publisher.put(payload);
                match timestamp {
                    Some(t) => put.timestamp(t).wait(),
                    None => put.wait(),
                }
                .map_err(|e| e.to_string())
            });
        if self.pooled {
            let (shm, copied) = self.writer.counts();
            self.metrics.set_counter(metric::SENT_SHM, shm);
            self.metrics.set_counter(metric::SENT_COPY, copied);
        }
        match sent {
            Ok(()) => {
                self.metrics.add(metric::PUBLISHED, 1);
                true
            }
            Err(e) => {
                self.metrics.add(metric::PUBLISH_ERRORS, 1);
                tracing::warn!("publish {}: {e}", self.key);
                false
            }
        }
    }
}
