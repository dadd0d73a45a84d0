//! shroud into ROS 2: each verdict of the arm as a `DiagnosticStatus` and a
//! speed scale (one of each per verdict, reliably, in zenoh's callback), the
//! arm's shapes coloured by that verdict as markers, the surrogates as
//! markers and the clouds as `PointCloud2` (the newest of each stream, at
//! most `--max-rate` a second), and the cloud frame's mount on `/tf_static`.

use super::ros_graph::RosPublisher;
use crate::node::viewer::Inbox;
use crate::runtime::NodeContext;
use crate::transport::{monotonic_ns, unix_ns};
use shroud_graph::metrics::names as metric;
use shroud_graph::pace::Paced;
use shroud_guard::ArmModel;
use shroud_msg::{CloudView, CollisionMessage, TopicKey, TopicKind};
use shroud_ros2::{RosMessage, TFMessage};
use shroud_ros2_bridge::{
    arm_markers, mount_transform, point_cloud2_of, speed_scale_of, surrogate_markers,
    verdict_status, CloudMount,
};
use shroud_surrogate::SurrogateWire;
use shroud_viewers::scene::RecentJoints;
use std::collections::BTreeMap;
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// Sends `message` on `publisher`, counting what was sent and what failed.
pub fn send(ctx: &NodeContext, publisher: &RosPublisher, message: &impl RosMessage) {
    match publisher.put(message.encode()) {
        Ok(()) => ctx.metrics.add(metric::ROS2_SENT, 1),
        Err(e) => {
            ctx.metrics.add(metric::PUBLISH_ERRORS, 1);
            tracing::warn!("{e}");
        }
    }
}

/// The verdict's publishers and what the arm's markers need.
pub struct VerdictOutput {
    pub status: RosPublisher,
    pub speed: RosPublisher,
    pub shapes: RosPublisher,
    pub model: ArmModel,
    pub frame_id: String,
    pub latest_joints: Arc<Mutex<RecentJoints>>,
    pub pace_ns: u64,
    pub last_shapes_ns: Mutex<Option<u64>>,
}

impl VerdictOutput {
    /// One verdict: its status and speed scale at once, the arm's shapes at
    /// most every `pace_ns`.
    pub fn on_verdict(&self, ctx: &NodeContext, verdict: &CollisionMessage) {
        send(ctx, &self.status, &verdict_status(verdict));
        send(ctx, &self.speed, &speed_scale_of(verdict));
        // The pose the verdict answered: drawn on a later pose, its colours
        // would describe clearances that pose never had.
        let joints = self
            .latest_joints
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .stamped(verdict.joints_stamp_ns)
            .cloned();
        let Some(joints) = joints else {
            return;
        };
        let now = monotonic_ns();
        {
            let mut last = self
                .last_shapes_ns
                .lock()
                .unwrap_or_else(|p| p.into_inner());
            if last.is_some_and(|t| now.saturating_sub(t) < self.pace_ns) {
                return;
            }
            *last = Some(now);
        }
        match shroud_viewers::scene::pose_arm(&self.model, &joints) {
            Ok(posed) => {
                let markers = arm_markers(&posed, Some(verdict), &self.frame_id, joints.stamp_ns);
                send(ctx, &self.shapes, &markers);
            }
            Err(e) => tracing::warn!("arm markers: {e}"),
        }
    }
}

/// The heavy streams' publishers.
pub struct StreamOutputs {
    pub surrogates: Option<RosPublisher>,
    /// One publisher per shroud cloud stream.
    pub clouds: BTreeMap<String, RosPublisher>,
    pub frame_id: String,
    pub per_cell: usize,
    pub pace_ns: u64,
    pub tf: Option<MountTransform>,
}

/// The ROS cloud frame's mount, sent on `/tf_static` once the frame's name
/// is known (from the first cloud).
pub struct MountTransform {
    pub publisher: RosPublisher,
    pub mount: CloudMount,
    pub frame: Arc<Mutex<Option<String>>>,
}

/// How often `/tf_static` is sent again (a late subscriber gets it within this).
const TF_PERIOD_NS: u64 = 1_000_000_000;

impl StreamOutputs {
    /// Sends the newest sample of each stream, paced, until the node stops.
    pub fn run(&self, ctx: &NodeContext, inbox: &Inbox) {
        let mut paced: Paced<String, (TopicKey, Vec<u8>)> = Paced::new(self.pace_ns);
        let mut next_tf = 0;
        while !ctx.stopping() {
            if let Some((key, arrival)) = inbox.take(Duration::from_millis(50)) {
                let stream = format!("{}/{}", key.kind, key.name);
                let item = (key, arrival.payload.to_bytes().to_vec());
                if let Some((key, payload)) = paced.offer(stream, item, monotonic_ns()) {
                    self.draw(ctx, &key, &payload);
                }
            }
            for (_, (key, payload)) in paced.release(monotonic_ns()) {
                self.draw(ctx, &key, &payload);
            }
            ctx.metrics
                .set_counter(metric::PACED_SUPERSEDED, paced.superseded());
            if monotonic_ns() >= next_tf {
                self.send_tf(ctx);
                next_tf = monotonic_ns() + TF_PERIOD_NS;
            }
        }
    }

    fn draw(&self, ctx: &NodeContext, key: &TopicKey, payload: &[u8]) {
        let label = format!("{}/{}", key.kind, key.name);
        match key.kind {
            TopicKind::Surrogate => {
                let Some(publisher) = &self.surrogates else {
                    return;
                };
                match shroud_msg::SurrogateMessage::from_bytes(payload) {
                    Ok((msg, surrogate)) => {
                        let markers = surrogate_markers(
                            &key.name,
                            &msg,
                            &surrogate,
                            &self.frame_id,
                            self.per_cell,
                        );
                        send(ctx, publisher, &markers);
                    }
                    Err(e) => ctx.drop_malformed(&label, &e),
                }
            }
            TopicKind::Cloud => {
                let Some(publisher) = self.clouds.get(&key.name) else {
                    return;
                };
                match CloudView::from_bytes(payload)
                    .and_then(|c| point_cloud2_of(&c, &self.frame_id))
                {
                    Ok(cloud) => send(ctx, publisher, &cloud),
                    Err(e) => ctx.drop_malformed(&label, &e),
                }
            }
            _ => {}
        }
    }

    fn send_tf(&self, ctx: &NodeContext) {
        let Some(tf) = &self.tf else {
            return;
        };
        let Some(child) = tf.frame.lock().unwrap_or_else(|p| p.into_inner()).clone() else {
            return;
        };
        let transforms = vec![mount_transform(
            &self.frame_id,
            &child,
            &tf.mount,
            unix_ns(),
        )];
        send(ctx, &tf.publisher, &TFMessage { transforms });
    }
}
