//! The bridge's Foxglove channels, created on a topic's first message (that
//! advertises it to every client) and kept by topic. A message is converted
//! only when some client subscribes to its channel: with no client, the
//! bridge costs the graph its subscriptions and nothing more.

use crate::to_foxglove::schema_of;
use foxglove::{Channel, Context, Encode};
use std::collections::BTreeMap;
use std::sync::Arc;

/// One kind of channel (one schema), by topic.
pub struct Channels<T: Encode> {
    context: Arc<Context>,
    by_topic: BTreeMap<String, Channel<T>>,
}

impl<T: Encode> Channels<T> {
    pub fn new(context: &Arc<Context>) -> Self {
        Self {
            context: context.clone(),
            by_topic: BTreeMap::new(),
        }
    }

    /// The channel of `topic`, advertised now if it is new.
    pub fn get(&mut self, topic: &str) -> &Channel<T> {
        self.by_topic.entry(topic.to_string()).or_insert_with(|| {
            self.context
                .channel_builder(topic)
                .schema(schema_of::<T>())
                .build::<T>()
        })
    }

    /// Whether a client subscribes to `topic` (advertising it if new).
    pub fn wanted(&mut self, topic: &str) -> bool {
        self.get(topic).has_sinks()
    }

    /// Logs what `make` builds on `topic` if a client subscribes to it;
    /// `make`'s error is the caller's to count. True if logged.
    pub fn log_with<E>(
        &mut self,
        topic: &str,
        make: impl FnOnce() -> Result<T, E>,
    ) -> Result<bool, E> {
        let channel = self.get(topic);
        if !channel.has_sinks() {
            return Ok(false);
        }
        channel.log(&make()?);
        Ok(true)
    }
}
