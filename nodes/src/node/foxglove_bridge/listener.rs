//! What Foxglove clients send the bridge: a JSON message on `/shroud/blend`
//! (`docs/formats.md`) is checked and forwarded as a `BlendCommandMessage` to the
//! blend node the bridge drives; anything else a client publishes is logged
//! and counted as malformed. A client's subscription asks the bridge to send
//! the channel's latest message again (a still surrogate would otherwise
//! reach a new client only when the fit changes it). Callbacks run on the
//! client's poll loop: each is a parse, a lock and at most one zenoh put.

use crate::node::viewer::BlendSender;
use crate::node::NodeContext;
use crate::to_foxglove::BLEND_TOPIC;
use foxglove::websocket::{ChannelView, Client, ClientChannel, ServerListener};
use shroud_graph::metrics::names as metric;
use shroud_msg::BlendRequest;
use shroud_shapes::blend::BlendCommand;
use shroud_viewers::dashboard::BlendPalette;
use std::collections::BTreeSet;
use std::sync::{Arc, Mutex, MutexGuard};

fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    // Each critical section is one read or insert.
    m.lock().unwrap_or_else(|p| p.into_inner())
}

/// State the bridge and the listener share.
#[derive(Default)]
pub struct Shared {
    /// The blend node to drive (from its status labels).
    pub palette: Mutex<Option<BlendPalette>>,
    /// Topics a client just subscribed to, to send again.
    pub resend: Mutex<BTreeSet<String>>,
}

impl Shared {
    pub fn take_resends(&self) -> BTreeSet<String> {
        std::mem::take(&mut lock(&self.resend))
    }
}

pub struct Listener {
    pub ctx: Arc<NodeContext>,
    pub shared: Arc<Shared>,
    pub blend: BlendSender,
}

impl Listener {
    /// The command a client's message asks for, or why it is refused.
    fn command(
        channel: &ClientChannel,
        payload: &[u8],
    ) -> Result<(BlendCommand, Option<String>), String> {
        if channel.topic != BLEND_TOPIC || channel.encoding != "json" {
            return Err(format!(
                "the bridge takes only {BLEND_TOPIC} in json, not {} in {}",
                channel.topic, channel.encoding
            ));
        }
        BlendRequest::from_json(payload)
            .and_then(BlendRequest::checked)
            .map_err(|e| e.to_string())
    }
}

impl ServerListener for Listener {
    fn on_message_data(&self, _client: Client, channel: &ClientChannel, payload: &[u8]) {
        self.ctx.metrics.add(metric::CLIENT_MESSAGES, 1);
        let (command, part) = match Self::command(channel, payload) {
            Ok(request) => request,
            Err(why) => {
                self.ctx
                    .drop_malformed(&format!("client {}", channel.topic), &why);
                return;
            }
        };
        let palette = lock(&self.shared.palette).clone();
        let sent = self
            .blend
            .send(&self.ctx, palette.as_ref(), &command, part.as_deref());
        if let Err(why) = sent {
            self.ctx.metrics.add(metric::BLEND_REFUSED, 1);
            tracing::warn!("a client's blend command was not sent: {why}");
        }
    }

    fn on_subscribe(&self, _client: Client, channel: ChannelView) {
        lock(&self.shared.resend).insert(channel.topic().to_string());
    }

    fn on_client_connect(&self) {
        self.ctx.metrics.add(metric::CLIENTS_CONNECTED, 1);
    }
}
