//! Waiting for Ctrl-C or SIGTERM, the two ways a node or launcher is asked to stop.

use std::future::Future;
use tokio::signal::unix::{signal, SignalKind};

/// Resolves on the first SIGINT or SIGTERM; returns the signal's name. The
/// handlers are installed when this is called (inside a runtime), not when the
/// future is first polled: a signal that arrives in between is seen, instead
/// of killing the process by its default action.
pub fn shutdown_signal() -> impl Future<Output = &'static str> {
    let streams = (
        signal(SignalKind::terminate()),
        signal(SignalKind::interrupt()),
    );
    async move {
        let (Ok(mut term), Ok(mut int)) = streams else {
            // Without signal handlers the process still dies on the default action.
            std::future::pending::<()>().await;
            return "none";
        };
        tokio::select! {
            _ = term.recv() => "SIGTERM",
            _ = int.recv() => "SIGINT",
        }
    }
}
