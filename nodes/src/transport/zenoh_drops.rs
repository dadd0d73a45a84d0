//! What zenoh dropped in this process (access control, congestion), read from
//! the session's own admin space: zenoh's `put` does not report either to
//! its caller, so every node, router and launcher publishes these counts in
//! its status.

use shroud_graph::metrics::ZenohDrops;
use std::time::Duration;

/// How long the local admin space may take to answer.
const ADMIN_TIMEOUT: Duration = Duration::from_millis(200);

/// The session's drop counts so far, or None when its admin space did not
/// answer (they are then left out of the status, not reported as zero).
pub async fn session_drops(session: &zenoh::Session) -> Option<ZenohDrops> {
    // Aggregated over transports, links and keys (closed ones included, so
    // the counts never go down), uncompressed, no comments. (The admin space
    // is the runtime's, not the session's, so `Locality::SessionLocal` would
    // find no one; a graph with access control lets no remote queryable be
    // declared under `@/`.)
    let key = format!(
        "@/{}/*/metrics?compression=false;descriptors=false;per_transport=false;per_link=false;per_key=false;disconnected=true",
        session.zid()
    );
    let replies = session.get(key).timeout(ADMIN_TIMEOUT).await.ok()?;
    let reply = replies.recv_async().await.ok()?;
    let sample = reply.result().ok()?;
    let text = String::from_utf8_lossy(&sample.payload().to_bytes()).into_owned();
    Some(ZenohDrops::from_openmetrics(&text))
}
