//! ROS 2 into shroud: a `PointCloud2` topic republished as a shroud cloud
//! stream (converted on a worker thread: a 300K-point cloud must not hold
//! up zenoh's callback, which also carries the joint states) and a
//! `JointState` topic as an arm's joint states (converted in the callback:
//! the guard answers each one). A sample without rmw_zenoh's attachment,
//! with an undecodable payload or a cloud or joint state that cannot be
//! used is logged and counted, never passed on.

use super::ros_graph::{RosNode, RosSubscription, RosTopic};
use crate::runtime::{NodeContext, NodeMetrics, Output};
use crate::transport::{monotonic_ns, unix_ns};
use anyhow::Result;
use shroud_graph::metrics::names as metric;
use shroud_msg::{CloudMessage, JointStateMessage};
use shroud_ros2::rmw::Attachment;
use shroud_ros2::{JointState, PointCloud2, RosMessage};
use shroud_ros2_bridge::{cloud_from_ros, CloudMount, JointMatcher};
use shroud_viewers::scene::RecentJoints;
use std::collections::BTreeSet;
use std::sync::mpsc::{sync_channel, Receiver, SyncSender, TrySendError};
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// A ROS sample as it arrived.
struct RosSample {
    key: String,
    payload: Vec<u8>,
    /// This node's monotonic clock at arrival.
    received_ns: u64,
    /// This node's wall clock at arrival.
    received_wall_ns: u64,
    /// Time since the ROS publisher sent it: its attachment's wall-clock
    /// stamp against ours (0 when its clock is ahead of ours: the clocks
    /// are assumed synchronised, as the guard's clock offset bound says).
    transit_ns: u64,
}

/// The sample's attachment, checked; `None` (counted and logged) when it is
/// missing or not rmw_zenoh's.
fn attachment(metrics: &NodeMetrics, key: &str, attachment: Option<&[u8]>) -> Option<Attachment> {
    let Some(bytes) = attachment else {
        metrics.add(metric::ROS2_BAD_ATTACHMENT, 1);
        tracing::warn!(key, "dropped a ROS sample without rmw_zenoh's attachment");
        return None;
    };
    match Attachment::decode(bytes) {
        Ok(a) => Some(a),
        Err(e) => {
            metrics.add(metric::ROS2_BAD_ATTACHMENT, 1);
            tracing::warn!(key, "dropped a ROS sample: attachment: {e}");
            None
        }
    }
}

fn arrival(key: &str, payload: &[u8], attachment: &Attachment) -> RosSample {
    // A stamp before the epoch counts the whole time since it: stale, never fresh.
    let sent = u64::try_from(attachment.source_timestamp_ns).unwrap_or(0);
    let received_wall_ns = unix_ns();
    RosSample {
        key: key.to_owned(),
        payload: payload.to_vec(),
        received_ns: monotonic_ns(),
        received_wall_ns,
        transit_ns: received_wall_ns.saturating_sub(sent),
    }
}

/// What the cloud input publishes into.
pub struct CloudInput {
    pub topic: RosTopic,
    pub output: Output<CloudMessage>,
    pub mount: CloudMount,
    pub source: String,
    /// The frame of the latest cloud, for `/tf_static`.
    pub frame: Arc<Mutex<Option<String>>>,
}

/// Subscribes to the cloud topic and converts on a worker thread until the
/// node stops; returns the subscription and the worker.
pub fn clouds_in(
    ros: &RosNode,
    ctx: &Arc<NodeContext>,
    input: CloudInput,
) -> Result<(RosSubscription, std::thread::JoinHandle<()>)> {
    // One cloud waits while one is converted; a third is dropped and counted.
    let (tx, rx): (SyncSender<RosSample>, Receiver<RosSample>) = sync_channel(1);
    let metrics = ctx.metrics.clone();
    let subscription = ros.subscribe(&input.topic, move |key, payload, att| {
        metrics.add(metric::ROS2_RECEIVED, 1);
        let Some(att) = attachment(&metrics, key, att) else {
            return;
        };
        if let Err(TrySendError::Full(_)) = tx.try_send(arrival(key, payload, &att)) {
            metrics.add(metric::DROPPED_BACKLOG, 1);
        }
    })?;
    let ctx = ctx.clone();
    let worker = std::thread::spawn(move || {
        let mut sequence = 0;
        while !ctx.stopping() {
            if let Ok(sample) = rx.recv_timeout(Duration::from_millis(100)) {
                publish_cloud(&ctx, &input, &sample, sequence);
                sequence += 1;
            }
        }
    });
    Ok((subscription, worker))
}

fn publish_cloud(ctx: &NodeContext, input: &CloudInput, sample: &RosSample, sequence: u64) {
    let cloud = match PointCloud2::decode_borrowed(&sample.payload) {
        Ok(cloud) => cloud,
        Err(e) => return ctx.drop_malformed(&sample.key, &format!("PointCloud2: {e}")),
    };
    let mut ros = match cloud_from_ros(&cloud, &input.mount, &input.source, sequence) {
        Ok(ros) => ros,
        Err(e) => return ctx.drop_malformed(&sample.key, &format!("PointCloud2: {e}")),
    };
    *input.frame.lock().unwrap_or_else(|p| p.into_inner()) = Some(cloud.header.frame_id.clone());
    ctx.metrics
        .add(metric::ROS2_EMPTY_RAYS, ros.empty_rays as u64);
    ctx.metrics
        .set(metric::POINTS, ros.message.points.len() as f64 / 12.0);
    // Counted from the earlier of the header's stamp (the driver's
    // acquisition, through any ROS filter nodes) and the last publisher's
    // send: whichever makes the cloud older.
    let since_stamp = sample.received_wall_ns.saturating_sub(ros.message.stamp_ns);
    ros.message.pipeline_ns =
        sample.transit_ns.max(since_stamp) + monotonic_ns().saturating_sub(sample.received_ns);
    input.output.put(&ros.message);
}

/// What the joint-state input publishes into.
pub struct JointsInput {
    pub topic: RosTopic,
    pub output: Output<JointStateMessage>,
    pub matcher: JointMatcher,
    /// The last joint states published, for the arm's markers.
    pub latest: Arc<Mutex<RecentJoints>>,
}

/// Subscribes to the joint-state topic; each usable one is published at once.
pub fn joints_in(
    ros: &RosNode,
    ctx: &Arc<NodeContext>,
    input: JointsInput,
) -> Result<RosSubscription> {
    let ctx = ctx.clone();
    let unknown_logged = Mutex::new(BTreeSet::new());
    let sequence = std::sync::atomic::AtomicU64::new(0);
    ros.subscribe(&input.topic.clone(), move |key, payload, att| {
        ctx.metrics.add(metric::ROS2_RECEIVED, 1);
        if attachment(&ctx.metrics, key, att).is_none() {
            return;
        }
        let state = match JointState::decode(payload) {
            Ok(state) => state,
            Err(e) => return ctx.drop_malformed(key, &format!("JointState: {e}")),
        };
        let n = sequence.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let matched = match input.matcher.match_joints(&state, n) {
            Ok(matched) => matched,
            Err(e) => return ctx.drop_malformed(key, &format!("JointState: {e}")),
        };
        if !matched.unknown.is_empty() {
            ctx.metrics
                .add(metric::ROS2_UNKNOWN_JOINTS, matched.unknown.len() as u64);
            let mut logged = unknown_logged.lock().unwrap_or_else(|p| p.into_inner());
            for name in matched
                .unknown
                .iter()
                .filter(|n| logged.insert((*n).clone()))
            {
                tracing::warn!(
                    key,
                    "joint {name:?} is not a joint of the arm: its values are dropped"
                );
            }
        }
        // Kept before it is sent: the verdict answering it may come back
        // before `put` returns.
        input
            .latest
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .push(matched.message.clone());
        input.output.put(&matched.message);
    })
}
