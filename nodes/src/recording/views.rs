//! What `shroud record --foxglove` stores beside the raw messages: the same
//! data as the Foxglove bridge serves it (`crate::to_foxglove`: clouds as
//! `foxglove.PointCloud`, surrogates and arms as `foxglove.SceneUpdate`, links
//! as `foxglove.FrameTransforms`, verdicts, certificates and status as JSON),
//! encoded with the schemas the `foxglove` crate declares, so that the file
//! opens in Foxglove or Lichtblick and shows the scene. Clouds, surrogates and
//! arms are drawn at most `--foxglove-rate` times a second per stream (by log
//! time; every raw message is recorded all the same). Verdicts are written
//! on every verdict and every 100 ms of log time between them, so that a
//! silent guard shows as `no-verdict` in the recording as on the bridge.

use crate::to_foxglove::{
    arm_scene, arm_scene_topic, arm_transforms, arm_transforms_topic, certificate_topic,
    certificate_view, cloud_topic, point_cloud, schema_of, status_topic, status_view,
    surrogate_scene, surrogate_topic, verdict_topic, verdict_view, vouched_bands, vouched_speed,
    SURFACE_PER_CELL, VERDICT_PERIOD_NS,
};
use foxglove::{Encode, Schema};
use shroud_guard::{ArmModel, VerdictWatch};
use shroud_msg::{
    CloudView, CollisionMessage, JointStateMessage, NodeStatusMessage, SurrogateMessage, TopicKey,
    TopicKind,
};
use shroud_surrogate::SurrogateWire;
use shroud_viewers::scene::pose_arm;
use std::collections::BTreeMap;

/// One Foxglove message ready for its channel.
pub struct View {
    pub topic: String,
    /// Its type's schema, built only when its channel is new (a JSON view's
    /// schema is derived anew each time: not once per message).
    schema_of: fn() -> Option<Schema>,
    pub message_encoding: String,
    pub data: Vec<u8>,
}

impl View {
    /// The schema of the view's type (`None` for a type without one).
    pub fn schema(&self) -> Option<Schema> {
        (self.schema_of)()
    }
}

/// Encodes `message` for `topic`; its schema is its type's.
fn view<T: Encode>(topic: String, message: &T) -> Result<View, String> {
    let mut data = Vec::with_capacity(message.encoded_len().unwrap_or(1024));
    message
        .encode(&mut data)
        .map_err(|e| format!("{topic}: cannot encode: {e}"))?;
    Ok(View {
        topic,
        schema_of: schema_of::<T>,
        message_encoding: T::get_message_encoding(),
        data,
    })
}

/// The views' settings.
pub struct ViewSettings {
    pub point_budget: usize,
    /// Least log time between two views of one cloud, surrogate or arm
    /// stream (`--foxglove-rate`): the raw messages are all recorded, their
    /// pictures at a viewer's rate.
    pub pace_ns: u64,
    pub arms: Vec<ArmModel>,
    pub verdict_timeout_ns: u64,
}

/// The conversions' settings and the state they keep between messages.
pub struct FoxgloveViews {
    settings: ViewSettings,
    watches: BTreeMap<String, VerdictWatch>,
    next_verdicts_ns: u64,
    /// Log time of each heavy stream's last view, by `<kind>/<name>`.
    last_view_ns: BTreeMap<String, u64>,
    paced: u64,
}

impl FoxgloveViews {
    /// Every arm of `--arm-file` has a verdict view from the start: a guard
    /// silent from the start shows as `no-verdict`, not as nothing.
    pub fn new(settings: ViewSettings) -> Self {
        let watches = settings
            .arms
            .iter()
            .map(|a| {
                (
                    a.name().to_string(),
                    VerdictWatch::new(settings.verdict_timeout_ns),
                )
            })
            .collect();
        Self {
            settings,
            watches,
            next_verdicts_ns: 0,
            last_view_ns: BTreeMap::new(),
            paced: 0,
        }
    }

    /// Messages of heavy streams left without a view by the pace.
    pub fn paced(&self) -> u64 {
        self.paced
    }

    /// Whether a view of `key`'s stream is due at `log_ns` (and if so, the
    /// stream's pace starts again).
    fn due(&mut self, key: &TopicKey, log_ns: u64) -> bool {
        let stream = format!("{}/{}", key.kind, key.name);
        let last = self.last_view_ns.get(&stream).copied();
        if last.is_some_and(|last| log_ns < last.saturating_add(self.settings.pace_ns)) {
            self.paced += 1;
            return false;
        }
        self.last_view_ns.insert(stream, log_ns);
        true
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
        let heavy = matches!(
            key.kind,
            TopicKind::Cloud | TopicKind::Surrogate | TopicKind::Joints
        );
        if heavy && !self.due(key, log_ns) {
            return Ok(Vec::new());
        }
        match key.kind {
            TopicKind::Cloud => {
                let view_of = CloudView::from_bytes(payload).map_err(|e| fail(&e))?;
                let cloud =
                    point_cloud(&view_of, self.settings.point_budget).map_err(|e| fail(&e))?;
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

    /// Whether [`Self::periodic`] would write anything at `log_ns`.
    pub fn verdicts_due(&self, log_ns: u64) -> bool {
        !self.watches.is_empty() && log_ns >= self.next_verdicts_ns
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
        let timeout = self.settings.verdict_timeout_ns;
        self.watches
            .entry(arm.to_owned())
            .or_insert_with(|| VerdictWatch::new(timeout))
    }

    /// The arm's shapes, coloured by the verdict the watch vouches for at
    /// `log_ns` (grey after a silence), and its links' frames; nothing for an
    /// arm without a model (`--arm-file`).
    fn arm_views(&mut self, msg: &JointStateMessage, log_ns: u64) -> Result<Vec<View>, String> {
        let Some(model) = self.settings.arms.iter().find(|a| a.name() == msg.arm) else {
            return Ok(Vec::new());
        };
        let posed = pose_arm(model, msg).map_err(|e| e.to_string())?;
        let watch = self.watches.get(&msg.arm);
        let (bands, speed) = (vouched_bands(watch, log_ns), vouched_speed(watch, log_ns));
        Ok(vec![
            view(
                arm_scene_topic(&msg.arm),
                &arm_scene(&posed, &bands, &speed, msg.stamp_ns),
            )?,
            view(
                arm_transforms_topic(&msg.arm),
                &arm_transforms(&posed, msg.stamp_ns),
            )?,
        ])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::to_foxglove::fixtures::collision;
    use shroud_msg::{CloudMessage, SensorPose};

    fn views() -> FoxgloveViews {
        FoxgloveViews::new(ViewSettings {
            point_budget: 1000,
            pace_ns: 100_000_000,
            arms: Vec::new(),
            verdict_timeout_ns: 500_000_000,
        })
    }

    fn key(kind: TopicKind, name: &str) -> TopicKey {
        TopicKey {
            namespace: "t".into(),
            kind,
            name: name.into(),
        }
    }

    #[test]
    fn heavy_streams_are_drawn_at_the_pace_and_the_rest_counted() {
        let mut v = views();
        let cloud = CloudMessage::new(1, 0, "s", SensorPose::default(), &[[0.0, 0.0, 1.0]; 10])
            .to_bytes()
            .unwrap();
        let k = key(TopicKind::Cloud, "a");
        let drawn: Vec<usize> = [0, 50, 99, 100, 150, 250]
            .iter()
            .map(|ms| v.of_message(&k, &cloud, ms * 1_000_000).unwrap().len())
            .collect();
        assert_eq!(drawn, [1, 0, 0, 1, 0, 1]);
        assert_eq!(v.paced(), 3);
        let views = v.of_message(&k, &cloud, 400_000_000).unwrap();
        assert_eq!(views[0].topic, "/shroud/cloud/a");
        assert_eq!(views[0].schema().unwrap().name, "foxglove.PointCloud");
        assert_eq!(views[0].message_encoding, "protobuf");
        // Another stream has its own pace; a cloud that does not decode is
        // an error naming it.
        let other = key(TopicKind::Cloud, "b");
        assert_eq!(v.of_message(&other, &cloud, 400_000_001).unwrap().len(), 1);
        let e = v
            .of_message(&key(TopicKind::Cloud, "c"), b"junk", 0)
            .err()
            .unwrap();
        assert!(e.starts_with("cloud/c"), "{e}");
    }

    #[test]
    fn a_silent_guard_shows_as_no_verdict_between_verdicts() {
        let mut v = views();
        let verdict = collision(&[("forearm", 0.2, false)]).to_bytes().unwrap();
        let k = key(TopicKind::Collision, "arm");
        let shown = v.of_message(&k, &verdict, 1_000_000_000).unwrap();
        let json =
            |view: &View| -> serde_json::Value { serde_json::from_slice(&view.data).unwrap() };
        assert_eq!(json(&shown[0])["verdict"], "clear");
        assert_eq!(json(&shown[0])["speed_scale"], 1.0);
        assert_eq!(json(&shown[0])["speed"], "full speed");
        assert_eq!(shown[0].schema().unwrap().name, "shroud.VerdictView");
        // 0.3 s later the verdict still stands; 0.6 s later it has expired.
        let fresh = v.periodic(1_300_000_000).unwrap();
        assert_eq!(json(&fresh[0])["verdict"], "clear");
        assert!(v.periodic(1_350_000_000).unwrap().is_empty(), "not yet due");
        let silent = v.periodic(1_600_000_000).unwrap();
        assert_eq!(json(&silent[0])["verdict"], "no-verdict");
        assert_eq!(json(&silent[0])["speed_scale"], 0.0);
        assert_eq!(silent[0].topic, "/shroud/verdict/arm");
    }
}
