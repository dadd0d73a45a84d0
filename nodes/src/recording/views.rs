//! What `shroud record --foxglove` stores beside the raw messages: the same
//! data as the Foxglove bridge serves it (`crate::to_foxglove`: clouds as
//! `foxglove.PointCloud`, surrogates and arms as `foxglove.SceneUpdate`, links
//! as `foxglove.FrameTransforms`, verdicts, certificates and status as JSON),
//! encoded with the schemas the `foxglove` crate declares, so that the file
//! opens in Foxglove or Lichtblick and shows the scene. Verdicts are written
//! on every verdict and every 100 ms of log time between them, so that a
//! silent guard shows as `no-verdict` in the recording as on the bridge.

use crate::to_foxglove::{
    arm_scene, arm_scene_topic, arm_transforms, arm_transforms_topic, certificate_topic,
    certificate_view, cloud_topic, link_bands, point_cloud, schema_of, status_topic, status_view,
    surrogate_scene, surrogate_topic, verdict_topic, verdict_view, SURFACE_PER_CELL,
};
use foxglove::{Encode, Schema};
use shroud_core::guard::{ArmModel, VerdictWatch};
use shroud_core::message::{
    CloudView, CollisionMessage, GuardVerdict, JointStateMessage, NodeStatusMessage,
    SurrogateMessage, TopicKey, TopicKind,
};
use shroud_core::scene::pose_arm;
use std::collections::BTreeMap;

/// How often, in log time, the verdict of every arm seen is written.
const VERDICT_PERIOD_NS: u64 = 100_000_000;

/// One Foxglove message ready for its channel.
pub struct View {
    pub topic: String,
    pub schema: Schema,
    pub message_encoding: String,
    pub data: Vec<u8>,
}

/// Encodes `message` with its type's schema for `topic`.
fn view<T: Encode>(topic: String, message: &T) -> Result<View, String> {
    let schema = schema_of::<T>().ok_or_else(|| format!("{topic}: no schema to record"))?;
    let mut data = Vec::with_capacity(message.encoded_len().unwrap_or(1024));
    message
        .encode(&mut data)
        .map_err(|e| format!("{topic}: cannot encode: {e}"))?;
    Ok(View {
        topic,
        schema,
        message_encoding: T::get_message_encoding(),
        data,
    })
}

/// The conversions' settings and the state they keep between messages.
pub struct FoxgloveViews {
    point_budget: usize,
    arms: Vec<ArmModel>,
    verdict_timeout_ns: u64,
    watches: BTreeMap<String, VerdictWatch>,
    next_verdicts_ns: u64,
}

impl FoxgloveViews {
    pub fn new(point_budget: usize, arms: Vec<ArmModel>, verdict_timeout_ns: u64) -> Self {
        Self {
            point_budget,
            arms,
            verdict_timeout_ns,
            watches: BTreeMap::new(),
            next_verdicts_ns: 0,
        }
    }

    /// The views of one recorded message received at `log_ns`; an error
    /// names the message that does not decode (the raw message is recorded
    /// all the same).
    pub fn of_message(
        &mut self,
        key: &TopicKey,
        payload: &[u8],
        log_ns: u64,
    ) -> Result<Vec<View>, String> {
        let fail = |e: &dyn std::fmt::Display| format!("{}/{}: {e}", key.kind, key.name);
        match key.kind {
            TopicKind::Cloud => {
                let view_of = CloudView::from_bytes(payload).map_err(|e| fail(&e))?;
                let cloud = point_cloud(&view_of, self.point_budget).map_err(|e| fail(&e))?;
                Ok(vec![view(cloud_topic(&key.name), &cloud)?])
            }
            TopicKind::Surrogate => {
                let (msg, surrogate) =
                    SurrogateMessage::from_bytes(payload).map_err(|e| fail(&e))?;
                let scene = surrogate_scene(&key.name, &msg, &surrogate, SURFACE_PER_CELL);
                Ok(vec![
                    view(surrogate_topic(&key.name), &scene)?,
                    view(
                        certificate_topic(&key.name),
                        &certificate_view(&key.name, &msg),
                    )?,
                ])
            }
            TopicKind::Joints => {
                let msg = JointStateMessage::from_bytes(payload).map_err(|e| fail(&e))?;
                self.arm_views(&msg, log_ns).map_err(|e| fail(&e))
            }
            TopicKind::Collision => {
                let msg = CollisionMessage::from_bytes(payload).map_err(|e| fail(&e))?;
                let arm = msg.arm.clone();
                let watch = self.watch(&arm);
                watch.on_verdict(msg, log_ns);
                Ok(vec![view(
                    verdict_topic(&arm),
                    &verdict_view(&arm, &watch.shown(log_ns)),
                )?])
            }
            TopicKind::Status => {
                let msg = NodeStatusMessage::from_bytes(payload).map_err(|e| fail(&e))?;
                Ok(vec![view(status_topic(&key.name), &status_view(&msg))?])
            }
            TopicKind::Smooth | TopicKind::Blend | TopicKind::Alive => Ok(Vec::new()),
        }
    }

    /// The verdict of every arm seen so far, if `VERDICT_PERIOD_NS` of log
    /// time passed since they were last written.
    pub fn periodic(&mut self, log_ns: u64) -> Result<Vec<View>, String> {
        if log_ns < self.next_verdicts_ns {
            return Ok(Vec::new());
        }
        self.next_verdicts_ns = log_ns + VERDICT_PERIOD_NS;
        self.watches
            .iter()
            .map(|(arm, watch)| view(verdict_topic(arm), &verdict_view(arm, &watch.shown(log_ns))))
            .collect()
    }

    fn watch(&mut self, arm: &str) -> &mut VerdictWatch {
        let timeout = self.verdict_timeout_ns;
        self.watches
            .entry(arm.to_owned())
            .or_insert_with(|| VerdictWatch::new(timeout))
    }

    /// The arm's shapes, coloured by the verdict the watch vouches for at
    /// `log_ns` (grey after a silence), and its links' frames; nothing for an
    /// arm without a model (`--arm-file`).
    fn arm_views(&mut self, msg: &JointStateMessage, log_ns: u64) -> Result<Vec<View>, String> {
        let Some(model) = self.arms.iter().find(|a| a.name() == msg.arm) else {
            return Ok(Vec::new());
        };
        let posed = pose_arm(model, msg).map_err(|e| e.to_string())?;
        let bands = self
            .watches
            .get(&msg.arm)
            .map(|w| w.shown(log_ns))
            .filter(|shown| shown.verdict != GuardVerdict::NoVerdict)
            .and_then(|shown| shown.message.map(link_bands))
            .unwrap_or_default();
        Ok(vec![
            view(
                arm_scene_topic(&msg.arm),
                &arm_scene(&posed, &bands, msg.stamp_ns),
            )?,
            view(
                arm_transforms_topic(&msg.arm),
                &arm_transforms(&posed, msg.stamp_ns),
            )?,
        ])
    }
}
