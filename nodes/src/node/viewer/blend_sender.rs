//! Publishes a viewer's blend commands to the blend node of the palette (the
//! one the viewer drives), one publisher per blend stream, counting them.

use crate::node::NodeContext;
use crate::transport::unix_ns;
use shroud_graph::metrics::names as metric;
use shroud_msg::{BlendCommandMessage, TopicKind};
use shroud_shapes::blend::BlendCommand;
use shroud_viewers::dashboard::BlendPalette;
use std::collections::BTreeMap;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;
use zenoh::Wait;

/// See the module documentation.
#[derive(Default)]
pub struct BlendSender {
    sequence: AtomicU64,
    publishers: Mutex<BTreeMap<String, zenoh::pubsub::Publisher<'static>>>,
}

impl BlendSender {
    /// Publishes `command` (a drop of `part`, if named) to `palette`'s blend
    /// node; an error says why not (no blend node, an unknown part).
    pub fn send(
        &self,
        ctx: &NodeContext,
        palette: Option<&BlendPalette>,
        command: &BlendCommand,
        part: Option<&str>,
    ) -> Result<(), String> {
        let Some(palette) = palette else {
            return Err("no blend node in this graph (start one: shroud node blend)".into());
        };
        if let Some(part) = part {
            if !palette.parts.iter().any(|p| p == part) {
                return Err(format!(
                    "the blend node has no part {part:?} (it has {})",
                    palette.parts.join(", ")
                ));
            }
        }
        let sequence = self.sequence.fetch_add(1, Ordering::Relaxed);
        let mut msg = BlendCommandMessage::new(unix_ns(), sequence, command);
        msg.part = part.map(String::from);
        let bytes = msg.to_bytes().map_err(|e| e.to_string())?;
        let mut publishers = self.publishers.lock().unwrap_or_else(|p| p.into_inner());
        if !publishers.contains_key(&palette.stream) {
            let publisher = ctx
                .publisher(TopicKind::Blend, &palette.stream)
                .map_err(|e| format!("{e:#}"))?;
            publishers.insert(palette.stream.clone(), publisher);
        }
        let publisher = &publishers[&palette.stream];
        publisher
            .put(bytes)
            .wait()
            .map_err(|e| format!("publish: {e}"))?;
        ctx.metrics.add(metric::BLEND_COMMANDS, 1);
        Ok(())
    }
}
