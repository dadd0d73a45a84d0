//! What the viewer nodes (the web dashboard, the Foxglove bridge) share: the
//! inbox of the graph's latest samples, the subscriptions that fill it, the
//! nodes' liveliness, and the sender of a viewer's blend commands.

mod blend_sender;
mod graph;
mod inbox;

pub use blend_sender::BlendSender;
pub use graph::{subscribe_drawables, watch_tokens};
pub use inbox::{Arrival, Inbox};
