//! The Foxglove topic of each shroud stream, in one place so that the bridge
//! and a recording name them alike.

/// Where a Foxglove client publishes blend commands (JSON, `docs/formats.md`).
pub const BLEND_TOPIC: &str = "/shroud/blend";

/// `foxglove.PointCloud` of cloud stream `stream`.
pub fn cloud_topic(stream: &str) -> String {
    format!("/shroud/cloud/{stream}")
}

/// `foxglove.SceneUpdate` of the surrogate on stream `stream`.
pub fn surrogate_topic(stream: &str) -> String {
    format!("/shroud/surrogate/{stream}")
}

/// JSON certificates of the surrogate on stream `stream`.
pub fn certificate_topic(stream: &str) -> String {
    format!("/shroud/certificate/{stream}")
}

/// `foxglove.SceneUpdate` of arm `arm`'s collision shapes.
pub fn arm_scene_topic(arm: &str) -> String {
    format!("/shroud/arm/{arm}")
}

/// `foxglove.FrameTransforms` of arm `arm`'s links.
pub fn arm_transforms_topic(arm: &str) -> String {
    format!("/shroud/tf/{arm}")
}

/// JSON verdicts of the guard watching arm `arm`.
pub fn verdict_topic(arm: &str) -> String {
    format!("/shroud/verdict/{arm}")
}

/// JSON status of node `node`.
pub fn status_topic(node: &str) -> String {
    format!("/shroud/status/{node}")
}
