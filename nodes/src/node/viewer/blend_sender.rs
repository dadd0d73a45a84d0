//! Publishes a viewer's blend commands to the blend node of the palette (the
//! one the viewer drives), one publisher per blend stream, counting them.

use crate::node::NodeContext;
use crate::runtime::Output;
use crate::transport::unix_ns;
use shroud_graph::metrics::names as metric;
use shroud_msg::BlendCommandMessage;
use shroud_shapes::blend::BlendCommand;
use shroud_viewers::dashboard::BlendPalette;
use std::collections::BTreeMap;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;

/// See the module documentation.
#[derive(Default)]
pub struct BlendSender {
    sequence: AtomicU64,
    outputs: Mutex<BTreeMap<String, Output<BlendCommandMessage>>>,
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
        let mut outputs = self.outputs.lock().unwrap_or_else(|p| p.into_inner());
        if !outputs.contains_key(&palette.stream) {
            let output = ctx
                .output::<BlendCommandMessage>(&palette.stream)
                .map_err(|e| format!("{e:#}"))?;
            outputs.insert(palette.stream.clone(), output);
        }
        let output = &outputs[&palette.stream];
        if !output.put(&msg) {
            return Err(format!(
                "could not publish on {} (see the node's log)",
                output.key()
            ));
        }
        ctx.metrics.add(metric::BLEND_COMMANDS, 1);
        Ok(())
    }
}
