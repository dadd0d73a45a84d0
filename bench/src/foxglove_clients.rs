//! Foxglove WebSocket clients for `shroud-bench consumers`: each offers the
//! `foxglove.sdk.v1` subprotocol, subscribes to every channel the bridge
//! advertises (now and later) and takes every binary frame, as a Foxglove
//! app on another machine would (it draws nothing here).

use anyhow::{Context, Result};
use futures_util::{SinkExt, StreamExt};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;
use tokio_tungstenite::tungstenite::client::IntoClientRequest;
use tokio_tungstenite::tungstenite::http::HeaderValue;
use tokio_tungstenite::tungstenite::Message;

/// Connected clients, reading until [`Self::stop`].
pub struct FoxgloveClients {
    tasks: Vec<tokio::task::JoinHandle<u64>>,
    stop: Arc<AtomicBool>,
}

/// The subscribe request for every channel of an `advertise` message.
fn subscribe_all(text: &str, next_id: &mut u64) -> Option<String> {
    let msg: serde_json::Value = serde_json::from_str(text).ok()?;
    if msg["op"] != "advertise" {
        return None;
    }
    let subscriptions: Vec<serde_json::Value> = msg["channels"]
        .as_array()?
        .iter()
        .filter_map(|c| c["id"].as_u64())
        .map(|channel| {
            *next_id += 1;
            serde_json::json!({"id": *next_id, "channelId": channel})
        })
        .collect();
    Some(serde_json::json!({"op": "subscribe", "subscriptions": subscriptions}).to_string())
}

impl FoxgloveClients {
    pub async fn connect(url: &str, count: usize) -> Result<Self> {
        let stop = Arc::new(AtomicBool::new(false));
        let mut tasks = Vec::new();
        for _ in 0..count {
            let mut request = url.into_client_request()?;
            request.headers_mut().insert(
                "Sec-WebSocket-Protocol",
                HeaderValue::from_static("foxglove.sdk.v1"),
            );
            let (mut socket, _) = tokio_tungstenite::connect_async(request)
                .await
                .with_context(|| format!("cannot connect to {url}"))?;
            let stop = stop.clone();
            tasks.push(tokio::spawn(async move {
                let (mut frames, mut next_id) = (0u64, 0u64);
                while !stop.load(Ordering::Relaxed) {
                    let next =
                        tokio::time::timeout(Duration::from_millis(200), socket.next()).await;
                    match next {
                        Ok(Some(Ok(Message::Text(text)))) => {
                            if let Some(request) = subscribe_all(&text, &mut next_id) {
                                if socket.send(Message::text(request)).await.is_err() {
                                    break;
                                }
                            }
                        }
                        Ok(Some(Ok(Message::Binary(_)))) => frames += 1,
                        Ok(Some(Ok(_))) | Err(_) => {}
                        Ok(Some(Err(_)) | None) => break,
                    }
                }
                frames
            }));
        }
        Ok(Self { tasks, stop })
    }

    /// Stops every client; the message frames they took.
    pub async fn stop(self) -> u64 {
        self.stop.store(true, Ordering::Relaxed);
        let mut frames = 0;
        for task in self.tasks {
            frames += task.await.unwrap_or(0);
        }
        frames
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_advertised_channel_is_subscribed_once() {
        let mut next = 0;
        let advertise =
            r#"{"op":"advertise","channels":[{"id":3,"topic":"/a"},{"id":9,"topic":"/b"}]}"#;
        let request: serde_json::Value =
            serde_json::from_str(&subscribe_all(advertise, &mut next).unwrap()).unwrap();
        assert_eq!(request["subscriptions"][1]["channelId"], 9);
        assert_eq!(request["subscriptions"][1]["id"], 2);
        assert!(subscribe_all(r#"{"op":"serverInfo"}"#, &mut next).is_none());
    }
}
