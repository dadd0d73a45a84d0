//! The frames of docs/dashboard-protocol.md built from decoded messages: what the page draws
//! of clouds, surrogates, smooth fits, the arm, verdicts and the nodes.

use super::frame::{ArrayData, Frame};
use super::PROTOCOL_VERSION;
use crate::scene::{
    smooth_mesh, surrogate_meshes, ArmSpeed, ClearanceBand, Decimation, PosedArm, SceneError,
};
use serde_json::{json, Map, Value};
use shroud_graph::metrics::NodeRow;
use shroud_guard::ShownVerdict;
use shroud_msg::{
    CloudView, MessageError, NodeStatusMessage, SmoothPatchesMessage, SurrogateMessage,
};
use shroud_surrogate::Surrogate;
use std::collections::BTreeMap;

/// What the `hello` frame tells a new browser.
#[derive(Debug, Clone, PartialEq)]
pub struct Hello<'a> {
    pub namespace: &'a str,
    pub node: &'a str,
    pub point_budget: usize,
    pub blend: Option<&'a BlendPalette>,
    pub arms: Vec<&'a str>,
    pub stop_banner_after_ms: f64,
}

/// The blend node a page drives: its command stream, its output cloud
/// stream and its parts, from the labels of its status (`blend.stream`,
/// `blend.output`, `blend.parts`, comma-separated).
#[derive(Debug, Clone, PartialEq)]
pub struct BlendPalette {
    pub stream: String,
    pub output: String,
    pub parts: Vec<String>,
}

impl BlendPalette {
    /// The palette a blend node's status announces, `None` for other nodes.
    pub fn from_status(status: &NodeStatusMessage) -> Option<Self> {
        let label = |key: &str| status.labels.get(key).cloned();
        let stream = label("blend.stream")?;
        Some(Self {
            output: label("blend.output").unwrap_or_else(|| stream.clone()),
            parts: label("blend.parts")
                .map(|p| {
                    p.split(',')
                        .filter(|s| !s.is_empty())
                        .map(String::from)
                        .collect()
                })
                .unwrap_or_default(),
            stream,
        })
    }

    /// Puts `self` in `slot` unless a `wanted` stream is named and this is
    /// another blend node's; true if the slot changed.
    pub fn adopt(self, slot: &mut Option<Self>, wanted: Option<&str>) -> bool {
        if wanted.is_some_and(|w| w != self.stream) || slot.as_ref() == Some(&self) {
            return false;
        }
        *slot = Some(self);
        true
    }
}

/// The first frame of a connection (and again whenever the palette changes).
pub fn hello_frame(h: &Hello<'_>) -> Vec<u8> {
    let blend = h
        .blend
        .map(|b| json!({"stream": b.stream, "output": b.output, "parts": b.parts}))
        .unwrap_or(Value::Null);
    Frame::new("hello")
        .field("protocol", PROTOCOL_VERSION)
        .field("namespace", h.namespace)
        .field("node", h.node)
        .field("point_budget", h.point_budget)
        .field("blend", blend)
        .field("arms", h.arms.clone())
        .field("stop_banner_after_ms", h.stop_banner_after_ms)
        .encode()
}

/// What a cloud frame is built from.
#[derive(Debug, Clone, Copy)]
pub struct CloudFrameInput<'v, 'a> {
    pub stream: &'v str,
    pub view: &'v CloudView<'a>,
    pub budget: usize,
    /// The stream is a blend's output: intensity is each point's source.
    pub blend_sources: bool,
}

/// The cloud thinned to the budget, refusing a cloud with a non-finite
/// coordinate (as every consumer of the schema does).
pub fn cloud_frame(input: CloudFrameInput<'_, '_>) -> Result<Vec<u8>, MessageError> {
    let view = input.view;
    view.check_finite_points()?;
    let floats = view.points.as_chunks::<4>().0;
    let keep = Decimation::new(view.len(), input.budget);
    let mut positions = Vec::with_capacity(3 * keep.kept());
    let (mut min, mut max) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    for i in keep.indices() {
        for (axis, c) in floats[3 * i..3 * i + 3].iter().enumerate() {
            let x = f32::from_le_bytes(*c);
            min[axis] = min[axis].min(x);
            max[axis] = max[axis].max(x);
            positions.push(x);
        }
    }
    let bounds = if keep.kept() == 0 {
        Value::Null
    } else {
        json!({"min": min, "max": max})
    };
    let intensity = view.intensity.as_ref().map(|bytes| {
        let values = bytes.as_chunks::<4>().0;
        keep.indices()
            .map(|i| f32::from_le_bytes(values[i]))
            .map(|v| if v.is_finite() { v } else { 0.0 })
            .collect::<Vec<f32>>()
    });
    let mut frame = Frame::new("cloud")
        .field("stream", input.stream)
        .field("sequence", view.sequence)
        .field("stamp_ns", view.stamp_ns)
        .field("age_ms", view.pipeline_ns as f64 / 1e6)
        .field("points_total", keep.total())
        .field("points_sent", keep.kept())
        .field("bounds", bounds)
        .field("intensity", intensity.is_some())
        .field("blend_sources", input.blend_sources && intensity.is_some())
        .array("positions", ArrayData::F32(positions));
    if let Some(values) = intensity {
        frame = frame.array("intensity", ArrayData::F32(values));
    }
    Ok(frame.encode())
}

/// The surrogate's surfaces as trimmed meshes with their certificates.
pub fn surrogate_frame(
    stream: &str,
    msg: &SurrogateMessage,
    surrogate: &Surrogate,
    per_cell: usize,
) -> Vec<u8> {
    let meshes = surrogate_meshes(surrogate, per_cell);
    let surfaces: Vec<Value> = meshes
        .iter()
        .map(|m| {
            let c = &m.certificate;
            json!({
                "side": m.side.name(),
                "vertices": m.positions.len(),
                "triangles": m.indices.len() / 3,
                "certificate": {
                    "points_checked": c.points_checked, "violations": c.violations,
                    "min_gap": c.min_gap, "max_gap": c.max_gap, "mean_gap": c.mean_gap,
                    "corrected_points": c.corrected_points,
                }
            })
        })
        .collect();
    let mut frame = Frame::new("surrogate")
        .field("stream", stream)
        .field("sequence", msg.source_sequence)
        .field("fit_ms", msg.fit_ns as f64 / 1e6)
        .field("age_ms", msg.pipeline_ns as f64 / 1e6)
        .field("direction", msg.direction.to_vec())
        .field("grid", vec![msg.domain.cols, msg.domain.rows])
        .field("surfaces", surfaces);
    for m in meshes {
        let side = m.side.name();
        frame = frame
            .array(
                &format!("{side}.positions"),
                ArrayData::F32(m.positions.concat()),
            )
            .array(&format!("{side}.indices"), ArrayData::U32(m.indices));
    }
    frame.encode()
}

/// A smooth fit tessellated, `per_patch` quads per patch side.
pub fn smooth_frame(
    stream: &str,
    msg: &SmoothPatchesMessage,
    per_patch: usize,
) -> Result<Vec<u8>, SceneError> {
    let mesh = smooth_mesh(msg, per_patch)?;
    let positions: Vec<f32> = mesh.vertices.iter().flatten().map(|&x| x as f32).collect();
    let indices: Vec<u32> = mesh.triangles.iter().flatten().copied().collect();
    Ok(Frame::new("smooth")
        .field("stream", stream)
        .field("sequence", msg.source_sequence)
        .field("kind", msg.kind.as_str())
        .field("fit_ms", msg.fit_ns as f64 / 1e6)
        .field("error_max", msg.error_max)
        .field("error_rmse", msg.error_rmse)
        .field("points", msg.points)
        .field("outside", msg.outside)
        .array("positions", ArrayData::F32(positions))
        .array("indices", ArrayData::U32(indices))
        .encode())
}

/// The arm's links and collision shapes at its latest joint state.
pub fn arm_frame(arm: &PosedArm) -> Vec<u8> {
    let f = |x: f64| x as f32;
    let origins: Vec<f32> = arm
        .links
        .iter()
        .flat_map(|l| l.origin.to_array().map(f))
        .collect();
    let (mut spheres, mut sphere_links) = (Vec::new(), Vec::new());
    for (link, c, r) in arm.spheres() {
        spheres.extend([f(c.x), f(c.y), f(c.z), f(r)]);
        sphere_links.push(link as u32);
    }
    let (mut capsules, mut capsule_links) = (Vec::new(), Vec::new());
    for (link, a, b, r) in arm.capsules() {
        capsules.extend([f(a.x), f(a.y), f(a.z), f(b.x), f(b.y), f(b.z), f(r)]);
        capsule_links.push(link as u32);
    }
    let names: Vec<&str> = arm.links.iter().map(|l| l.name.as_str()).collect();
    Frame::new("arm")
        .field("arm", arm.arm.as_str())
        .field("joints_sequence", arm.joints_sequence)
        .field("links", names)
        .array("link_origins", ArrayData::F32(origins))
        .array("spheres", ArrayData::F32(spheres))
        .array("sphere_links", ArrayData::U32(sphere_links))
        .array("capsules", ArrayData::F32(capsules))
        .array("capsule_links", ArrayData::U32(capsule_links))
        .encode()
}

/// The verdict to show for `arm`, with each link's band and the arm's speed
/// ([`ArmSpeed`]: the scale is 0 for anything but a fresh `clear`; a silent
/// guard's last limiting link and `S_p` are `null`).
pub fn verdict_frame(arm: &str, shown: &ShownVerdict<'_>) -> Vec<u8> {
    let speed = ArmSpeed::of(shown);
    let mut frame = Frame::new("verdict")
        .field("arm", arm)
        .field("verdict", shown.verdict.name())
        .field("stop", shown.verdict != shroud_msg::GuardVerdict::Clear)
        .field("reason", shown.reason.as_str())
        .field("verdict_age_ms", shown.age_ns.map(|a| a as f64 / 1e6))
        .field("speed_scale", speed.scale)
        .field("limiting_link", speed.limiting_link)
        .field("protective_distance", speed.protective_distance);
    if let Some(msg) = shown.message {
        let links: Vec<Value> = msg
            .links
            .iter()
            .map(|l| {
                json!({
                    "link": l.link, "clearance": finite_or_null(l.clearance),
                    "unobserved": l.unobserved,
                    "band": ClearanceBand::of(l, msg.stop_distance).name(),
                })
            })
            .collect();
        frame = frame
            .field("min_clearance", finite_or_null(msg.min_clearance))
            .field("closest_link", msg.closest_link.as_str())
            .field("stop_distance", msg.stop_distance)
            .field("surrogate_age_ms", msg.surrogate_age_ns as f64 / 1e6)
            .field("joints_sequence", msg.joints_sequence)
            .field("links", links);
    }
    frame.encode()
}

/// JSON has no infinity: an unbounded clearance travels as `null`.
fn finite_or_null(x: f64) -> Value {
    if x.is_finite() {
        Value::from(x)
    } else {
        Value::Null
    }
}

/// One topic's traffic as the dashboard hears it.
#[derive(Debug, Clone, PartialEq)]
pub struct TopicRate {
    /// `<kind>/<name>`.
    pub topic: String,
    pub kind: String,
    pub rate_hz: f64,
    pub messages: u64,
    pub bytes_per_s: f64,
}

/// The dashboard's own counters.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DashboardCounts {
    pub clients: usize,
    pub frames_sent: u64,
    pub frames_superseded: u64,
    pub dropped_malformed: u64,
}

/// The nodes table, topic rates and the dashboard's counters.
pub fn nodes_frame(
    uptime_s: f64,
    rows: &[NodeRow<'_>],
    restarts: &BTreeMap<String, u64>,
    topics: &[TopicRate],
    counts: DashboardCounts,
) -> Vec<u8> {
    let nodes: Vec<Value> = rows.iter().map(|r| node_row(r, restarts)).collect();
    let topics: Vec<Value> = topics
        .iter()
        .map(|t| {
            json!({"topic": t.topic, "kind": t.kind, "rate_hz": t.rate_hz,
                   "messages": t.messages, "bytes_per_s": t.bytes_per_s})
        })
        .collect();
    Frame::new("nodes")
        .field("uptime_s", uptime_s)
        .field("nodes", nodes)
        .field("topics", topics)
        .field(
            "dashboard",
            json!({"clients": counts.clients, "frames_sent": counts.frames_sent,
                   "frames_superseded": counts.frames_superseded,
                   "dropped_malformed": counts.dropped_malformed}),
        )
        .encode()
}

fn node_row(row: &NodeRow<'_>, restarts: &BTreeMap<String, u64>) -> Value {
    let mut out = Map::new();
    out.insert("name".into(), row.name.into());
    out.insert("state".into(), row.state.name().into());
    out.insert(
        "restarts".into(),
        restarts.get(row.name).copied().unwrap_or(0).into(),
    );
    out.insert(
        "status_age_s".into(),
        row.status_age_ns.map(|a| a as f64 / 1e9).into(),
    );
    if let Some(s) = row.status {
        out.insert("kind".into(), s.kind.as_str().into());
        out.insert("pid".into(), s.pid.into());
        out.insert("uptime_s".into(), s.uptime_s.into());
        out.insert("counters".into(), json!(s.counters));
        out.insert("gauges".into(), json!(s.gauges));
        out.insert("labels".into(), json!(s.labels));
    }
    Value::Object(out)
}

/// The answer to a browser's blend command.
pub fn blend_result_frame(id: u64, outcome: Result<(), String>) -> Vec<u8> {
    let frame = Frame::new("blend_result").field("id", id);
    match outcome {
        Ok(()) => frame.field("ok", true),
        Err(e) => frame.field("ok", false).field("error", e),
    }
    .encode()
}

/// A browser's frame was refused.
pub fn error_frame(message: &str) -> Vec<u8> {
    Frame::new("error").field("message", message).encode()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dashboard::DecodedFrame;
    use shroud_graph::metrics::NodeHealth;
    use shroud_guard::VerdictWatch;
    use shroud_msg::{sample_collision, GuardVerdict, SensorPose};

    fn decoded(bytes: &[u8]) -> DecodedFrame {
        DecodedFrame::decode(bytes).expect("a frame the page can read")
    }

    #[test]
    fn a_cloud_is_thinned_to_the_budget_with_its_intensity() {
        let points: Vec<[f32; 3]> = (0..1000).map(|i| [i as f32, 0.0, -(i as f32)]).collect();
        let intensity: Vec<f32> = (0..1000).map(|i| (i % 3) as f32).collect();
        let view =
            CloudView::new(5, 6, "sim", SensorPose::default(), &points).with_intensity(&intensity);
        let bytes = cloud_frame(CloudFrameInput {
            stream: "blend",
            view: &view,
            budget: 100,
            blend_sources: true,
        })
        .unwrap();
        let f = decoded(&bytes);
        assert_eq!(f.kind(), "cloud");
        assert_eq!(
            (
                f.header["points_total"].as_u64(),
                f.header["points_sent"].as_u64()
            ),
            (Some(1000), Some(100))
        );
        assert_eq!(f.header["blend_sources"], true);
        let p = f.f32s(&bytes, "positions").unwrap();
        assert_eq!(p.len(), 300);
        assert_eq!(&p[3..6], &[10.0, 0.0, -10.0]);
        assert_eq!(f.f32s(&bytes, "intensity").unwrap()[1], 1.0);
        assert_eq!(f.header["bounds"]["max"][0], 990.0);
        let mut bad = points.clone();
        bad[500][1] = f32::NAN;
        let view = CloudView::new(5, 6, "sim", SensorPose::default(), &bad);
        let input = CloudFrameInput {
            stream: "s",
            view: &view,
            budget: 10,
            blend_sources: false,
        };
        assert_eq!(
            cloud_frame(input),
            Err(MessageError::NonFinite {
                field: "points",
                index: 500
            })
        );
    }

    #[test]
    fn a_verdict_frame_names_bands_and_a_silent_guard_is_no_verdict() {
        let mut watch = VerdictWatch::new(1_000);
        let mut msg = sample_collision(GuardVerdict::Stop);
        msg.links[0].clearance = 0.01;
        watch.on_verdict(msg, 0);
        let f = decoded(&verdict_frame("arm", &watch.shown(10)));
        assert_eq!(f.header["verdict"], "stop");
        assert_eq!(f.header["stop"], true);
        assert_eq!(f.header["links"][0]["band"], "stop");
        let f = decoded(&verdict_frame("arm", &watch.shown(5_000)));
        assert_eq!(f.header["verdict"], "no-verdict");
        assert_eq!(f.header["stop"], true);
        let empty = VerdictWatch::new(1);
        let f = decoded(&verdict_frame("arm", &empty.shown(0)));
        assert_eq!(f.header["verdict"], "no-verdict");
        assert!(f.header.get("links").is_none());
        assert_eq!(f.header["speed_scale"], 0.0);
        assert_eq!(f.header["limiting_link"], Value::Null);
    }

    #[test]
    fn a_verdict_frame_carries_the_speed_scale_its_limiting_link_and_s_p() {
        let mut watch = VerdictWatch::new(1_000);
        let mut msg = sample_collision(GuardVerdict::Clear);
        (msg.speed_scale, msg.limiting_link, msg.protective_distance) =
            (0.42, "forearm".into(), 0.84);
        watch.on_verdict(msg, 0);
        let f = decoded(&verdict_frame("arm", &watch.shown(10)));
        assert_eq!(
            (f.header["verdict"].as_str(), f.header["stop"].as_bool()),
            (Some("clear"), Some(false))
        );
        assert_eq!(f.header["speed_scale"], 0.42);
        assert_eq!(f.header["limiting_link"], "forearm");
        assert_eq!(f.header["protective_distance"], 0.84);
        // At full speed nothing limits it; a silent guard's numbers are gone.
        watch.on_verdict(sample_collision(GuardVerdict::Clear), 0);
        let f = decoded(&verdict_frame("arm", &watch.shown(10)));
        assert_eq!(f.header["speed_scale"], 1.0);
        assert_eq!(f.header["limiting_link"], Value::Null);
        assert_eq!(f.header["protective_distance"], 0.05);
        let f = decoded(&verdict_frame("arm", &watch.shown(5_000)));
        assert_eq!(f.header["verdict"], "no-verdict");
        assert_eq!(f.header["speed_scale"], 0.0);
        assert_eq!(f.header["protective_distance"], Value::Null);
        // A stop moves at 0, whatever its limiting link.
        let mut stop = sample_collision(GuardVerdict::Stop);
        stop.limiting_link = "tool".into();
        watch.on_verdict(stop, 0);
        let f = decoded(&verdict_frame("arm", &watch.shown(10)));
        assert_eq!(f.header["speed_scale"], 0.0);
        assert_eq!(f.header["limiting_link"], "tool");
    }

    #[test]
    fn the_nodes_frame_carries_state_restarts_and_rates() {
        let mut health = NodeHealth::default();
        health.on_token("fit", true);
        let mut status = NodeStatusMessage::new("fit", "fit", 42);
        status.counters.insert("received".into(), 3);
        health.on_status(status, 0);
        health.on_token("guard", false);
        let restarts = BTreeMap::from([("fit".to_string(), 2)]);
        let topics = [TopicRate {
            topic: "cloud/spheres".into(),
            kind: "cloud".into(),
            rate_hz: 10.0,
            messages: 30,
            bytes_per_s: 1e6,
        }];
        let counts = DashboardCounts {
            clients: 2,
            ..Default::default()
        };
        let f = decoded(&nodes_frame(
            1.5,
            &health.rows(1),
            &restarts,
            &topics,
            counts,
        ));
        let nodes = f.header["nodes"].as_array().unwrap();
        assert_eq!(nodes[0]["name"], "fit");
        assert_eq!(nodes[0]["state"], "alive");
        assert_eq!(nodes[0]["restarts"], 2);
        assert_eq!(nodes[0]["pid"], 42);
        assert_eq!(nodes[0]["counters"]["received"], 3);
        assert_eq!(nodes[1]["state"], "gone");
        assert_eq!(f.header["topics"][0]["rate_hz"], 10.0);
        assert_eq!(f.header["dashboard"]["clients"], 2);
    }

    #[test]
    fn the_palette_comes_from_a_blend_nodes_labels() {
        let mut status = NodeStatusMessage::new("blend", "blend", 1);
        assert_eq!(BlendPalette::from_status(&status), None);
        status.labels.insert("blend.stream".into(), "blend".into());
        status
            .labels
            .insert("blend.parts".into(), "hemisphere,scan.ply".into());
        let palette = BlendPalette::from_status(&status).unwrap();
        assert_eq!(palette.output, "blend");
        let mut slot = None;
        assert!(!palette.clone().adopt(&mut slot, Some("other")));
        assert!(palette.clone().adopt(&mut slot, Some("blend")));
        assert!(!palette.clone().adopt(&mut slot, None));
        assert_eq!(slot.as_ref(), Some(&palette));
        assert_eq!(palette.parts, vec!["hemisphere", "scan.ply"]);
        let hello = Hello {
            namespace: "demo",
            node: "dashboard",
            point_budget: 1000,
            blend: Some(&palette),
            arms: vec!["demo_arm"],
            stop_banner_after_ms: 500.0,
        };
        let f = decoded(&hello_frame(&hello));
        assert_eq!(f.header["protocol"], 2);
        assert_eq!(f.header["blend"]["parts"][1], "scan.ply");
        let f = decoded(&blend_result_frame(3, Err("off the surface".into())));
        assert_eq!(
            (f.header["ok"].as_bool(), f.header["error"].as_str()),
            (Some(false), Some("off the surface"))
        );
    }
}
