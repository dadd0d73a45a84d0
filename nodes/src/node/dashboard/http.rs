//! The dashboard's HTTP side (axum): the page's embedded files at `/`, and the
//! WebSocket at `/ws` where each browser gets its frames from the hub and
//! sends its commands (docs/dashboard-protocol.md).

use super::assets;
use super::builder::Shared;
use super::hub::{Browser, Hub};
use crate::node::viewer::BlendSender;
use crate::node::NodeContext;
use axum::extract::ws::{Message, WebSocket, WebSocketUpgrade};
use axum::extract::{Path, State};
use axum::http::{header, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::routing::get;
use axum::Router;
use shroud_graph::metrics::names as metric;
use shroud_viewers::dashboard::{blend_result_frame, error_frame, BrowserCommand};
use std::sync::atomic::Ordering;
use std::sync::Arc;

/// What every request handler shares.
#[derive(Clone)]
pub struct Http {
    pub ctx: Arc<NodeContext>,
    pub hub: Arc<Hub>,
    pub shared: Arc<Shared>,
    pub point_budget: usize,
    pub blend: Arc<BlendSender>,
}

/// The routes.
pub fn router(state: Http) -> Router {
    Router::new()
        .route("/", get(index))
        .route("/ws", get(upgrade))
        .route("/{*path}", get(asset))
        .with_state(state)
}

async fn index() -> Response {
    asset(Path("index.html".into())).await
}

async fn asset(Path(path): Path<String>) -> Response {
    match assets::get(&path) {
        Some((mime, bytes)) => (
            [
                (header::CONTENT_TYPE, mime),
                // The page is built into this binary: a new build is a new page.
                (header::CACHE_CONTROL, "no-cache"),
            ],
            bytes,
        )
            .into_response(),
        None => (
            StatusCode::NOT_FOUND,
            format!("no file {path:?} in the dashboard"),
        )
            .into_response(),
    }
}

async fn upgrade(ws: WebSocketUpgrade, State(http): State<Http>) -> Response {
    ws.on_upgrade(move |socket| serve_browser(socket, http))
}

/// One browser's connection: frames out as the hub gives them, commands in.
async fn serve_browser(mut socket: WebSocket, http: Http) {
    let browser = http.hub.join(http.point_budget);
    http.ctx.metrics.add(metric::BROWSERS_CONNECTED, 1);
    let hello = http
        .shared
        .hello
        .lock()
        .unwrap_or_else(|p| p.into_inner())
        .clone();
    browser.put("hello", Arc::new(hello));
    loop {
        tokio::select! {
            frame = browser.next_frame() => {
                let Some((_, frame)) = frame else { break };
                if socket.send(Message::Binary(frame.as_ref().clone().into())).await.is_err() {
                    break;
                }
                http.hub.frames_sent.fetch_add(1, Ordering::Relaxed);
            }
            incoming = socket.recv() => match incoming {
                Some(Ok(Message::Text(text))) => on_command(&http, &browser, text.as_str()).await,
                Some(Ok(Message::Binary(_))) => refuse(&http, &browser, "binary frames are not commands: send JSON text"),
                Some(Ok(_)) => {} // ping, pong: axum answers pings itself
                Some(Err(_)) | None => break,
            },
        }
    }
    http.hub.leave(&browser);
}

/// A browser's text frame.
async fn on_command(http: &Http, browser: &Browser, text: &str) {
    match BrowserCommand::parse(text) {
        Ok(BrowserCommand::Options { point_budget }) => {
            let budget = (point_budget as usize).clamp(1000, http.point_budget.max(1000));
            browser.set_budget(budget);
        }
        Ok(BrowserCommand::Blend { id, command, part }) => {
            let palette = http
                .shared
                .palette
                .lock()
                .unwrap_or_else(|p| p.into_inner())
                .clone();
            let outcome = http
                .blend
                .send(&http.ctx, palette.as_ref(), &command, part.as_deref());
            browser.put(
                &format!("blend_result/{id}"),
                Arc::new(blend_result_frame(id, outcome)),
            );
        }
        Err(e) => refuse(http, browser, &e.to_string()),
    }
}

fn refuse(http: &Http, browser: &Browser, why: &str) {
    http.ctx.drop_malformed("browser", &why);
    let n = http.ctx.metrics.counter(metric::DROPPED_MALFORMED);
    browser.put(&format!("error/{n}"), Arc::new(error_frame(why)));
}
