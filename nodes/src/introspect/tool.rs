//! What the introspection tools share: a session that is not a node (no
//! liveliness token, no status) and the topic-name shorthand.

use crate::transport::ZenohArgs;
use anyhow::Result;
use clap::Args;
use shroud_msg::Topics;

#[derive(Debug, Clone, Args)]
pub struct ToolArgs {
    #[command(flatten)]
    pub zenoh: ZenohArgs,
}

impl ToolArgs {
    /// A current-thread runtime is enough for a tool.
    pub fn block_on<F: std::future::Future<Output = Result<()>>>(&self, body: F) -> Result<()> {
        tokio::runtime::Builder::new_multi_thread()
            .worker_threads(1)
            .enable_all()
            .build()?
            .block_on(body)
    }
}

/// `cloud/sim` → `shroud/<ns>/cloud/sim`; a key starting with `shroud/` is kept.
pub fn resolve_topic(topics: &Topics, topic: &str) -> Result<String> {
    if topic.starts_with("shroud/") {
        return Ok(topic.to_string());
    }
    anyhow::ensure!(
        !topic.is_empty() && !topic.starts_with('/'),
        "topic {topic:?} must be <kind>/<name> (e.g. cloud/sim) or a full shroud/... key"
    );
    Ok(format!("shroud/{}/{topic}", topics.namespace()))
}
