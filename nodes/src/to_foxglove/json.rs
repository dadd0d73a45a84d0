//! JSON views of verdicts, certificates and node status for Foxglove's Plot
//! and Raw Message panels: flat, named numeric fields (`min_clearance`,
//! `upper.min_gap`, `counters.received`), JSON's `null` where a number is
//! infinite or NaN (JSON has neither). Each derives its JSON Schema, which
//! the channel advertises (`docs/formats.md`, "Foxglove channels").

use schemars::JsonSchema;
use serde::Serialize;
use shroud_guard::ShownVerdict;
use shroud_msg::{GuardVerdict, NodeStatusMessage, SurrogateMessage};
use shroud_surrogate::{Certificate, Side};
use shroud_viewers::scene::{ArmSpeed, ClearanceBand};
use std::collections::BTreeMap;

/// What an arm's guard says, as a viewer shows it (a silent guard is
/// `no-verdict`, a stop).
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct VerdictView {
    pub arm: String,
    /// `clear`, `stop`, `stale`, `no-verdict`... (the guard's verdict names).
    pub verdict: String,
    pub stop: bool,
    pub reason: String,
    /// Milliseconds since the verdict arrived; null before the first.
    pub verdict_age_ms: Option<f64>,
    /// Metres; null when no verdict or nothing bounds it.
    pub min_clearance: Option<f64>,
    pub closest_link: Option<String>,
    pub stop_distance: Option<f64>,
    pub surrogate_age_ms: Option<f64>,
    pub joints_sequence: Option<u64>,
    /// The fraction, in [0, 1], of each joint's velocity limit the verdict
    /// lets the arm move at: the guard's `speed_scale` for a `clear`, 0 for
    /// every other verdict (`no-verdict` included).
    pub speed_scale: f64,
    /// `full`, `scaled` or `stopped`.
    pub speed_state: String,
    /// One line: `full speed`, `62 % speed, limited by forearm (S_p 0.840
    /// m)`, `stopped (stop)`.
    pub speed: String,
    /// The link whose separation limits the scale; null when the verdict
    /// names none or is `no-verdict`.
    pub limiting_link: Option<String>,
    /// Metres: the verdict's protective separation distance `S_p` (the
    /// limiting link's at the scale, else the stop distance); null for
    /// `no-verdict`.
    pub protective_distance: Option<f64>,
    pub links: Vec<LinkView>,
}

/// One link's clearance in a verdict.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct LinkView {
    pub link: String,
    pub clearance: Option<f64>,
    pub unobserved: bool,
    /// `stop`, `near`, `clear` or `unobserved` ([`ClearanceBand`]).
    pub band: String,
}

/// How often verdict views go out, on the bridge and in recordings: a guard
/// that falls silent shows as `no-verdict` within this of its timeout.
pub const VERDICT_PERIOD_NS: u64 = 100_000_000;

/// The verdict shown for `arm`.
pub fn verdict_view(arm: &str, shown: &ShownVerdict<'_>) -> VerdictView {
    let msg = shown.message;
    let speed = ArmSpeed::of(shown);
    VerdictView {
        arm: arm.into(),
        verdict: shown.verdict.name().into(),
        stop: shown.verdict != GuardVerdict::Clear,
        reason: shown.reason.clone(),
        verdict_age_ms: shown.age_ns.map(|a| a as f64 / 1e6),
        min_clearance: msg.and_then(|m| finite(m.min_clearance)),
        closest_link: msg.map(|m| m.closest_link.clone()),
        stop_distance: msg.map(|m| m.stop_distance),
        surrogate_age_ms: msg.map(|m| m.surrogate_age_ns as f64 / 1e6),
        joints_sequence: msg.map(|m| m.joints_sequence),
        speed_scale: speed.scale,
        speed_state: speed.state.name().into(),
        speed: speed.label(),
        limiting_link: speed.limiting_link,
        protective_distance: speed.protective_distance,
        links: msg
            .map(|m| {
                m.links
                    .iter()
                    .map(|l| LinkView {
                        link: l.link.clone(),
                        clearance: finite(l.clearance),
                        unobserved: l.unobserved,
                        band: ClearanceBand::of(l, m.stop_distance).name().into(),
                    })
                    .collect()
            })
            .unwrap_or_default(),
    }
}

/// A surrogate's certificates, one field per side so that a plot path reads
/// `upper.min_gap`.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct CertificateView {
    pub stream: String,
    /// Sequence and stamp of the cloud the surrogate certifies.
    pub source_sequence: u64,
    pub source_stamp_ns: u64,
    /// The fitting direction (unit x, y, z).
    pub direction: [f64; 3],
    pub fit_ms: f64,
    /// The cloud's time in shroud nodes up to the surrogate's publication.
    pub age_ms: f64,
    pub upper: Option<SurfaceCertificate>,
    pub lower: Option<SurfaceCertificate>,
}

/// One certified surface's check against its cloud (paper 002's certificate).
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct SurfaceCertificate {
    /// `upper` or `lower`.
    pub side: String,
    pub points_checked: u64,
    /// Points on the wrong side of the surface: 0 for a valid certificate.
    pub violations: u64,
    /// Gaps `sign * (f(s,t) - w)` between surface and points, metres.
    pub min_gap: Option<f64>,
    pub mean_gap: Option<f64>,
    pub max_gap: Option<f64>,
    pub corrected_points: u64,
}

/// The certificates `msg` carries (published on `stream`).
pub fn certificate_view(stream: &str, msg: &SurrogateMessage) -> CertificateView {
    let side = |side: Side| {
        msg.surfaces
            .iter()
            .find(|s| s.side == side)
            .map(|s| surface_certificate(&s.certificate))
    };
    CertificateView {
        stream: stream.into(),
        source_sequence: msg.source_sequence,
        source_stamp_ns: msg.source_stamp_ns,
        direction: msg.direction,
        fit_ms: msg.fit_ns as f64 / 1e6,
        age_ms: msg.pipeline_ns as f64 / 1e6,
        upper: side(Side::Upper),
        lower: side(Side::Lower),
    }
}

fn surface_certificate(c: &Certificate) -> SurfaceCertificate {
    SurfaceCertificate {
        side: c.side.name().into(),
        points_checked: c.points_checked,
        violations: c.violations,
        min_gap: finite(c.min_gap),
        mean_gap: finite(c.mean_gap),
        max_gap: finite(c.max_gap),
        corrected_points: c.corrected_points,
    }
}

/// A node's status message.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct StatusView {
    pub node: String,
    pub kind: String,
    pub pid: u32,
    pub stamp_ns: u64,
    pub uptime_s: f64,
    /// Monotonic counts (`received`, `published`, `dropped_malformed`...).
    pub counters: BTreeMap<String, u64>,
    /// Latest measurements (`rate_hz`, `fit_ms`...); null when not finite.
    pub gauges: BTreeMap<String, Option<f64>>,
    pub labels: BTreeMap<String, String>,
}

pub fn status_view(msg: &NodeStatusMessage) -> StatusView {
    StatusView {
        node: msg.node.clone(),
        kind: msg.kind.clone(),
        pid: msg.pid,
        stamp_ns: msg.stamp_ns,
        uptime_s: msg.uptime_s,
        counters: msg.counters.clone(),
        gauges: msg
            .gauges
            .iter()
            .map(|(k, v)| (k.clone(), finite(*v)))
            .collect(),
        labels: msg.labels.clone(),
    }
}

fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::to_foxglove::fixtures::collision;
    use shroud_guard::VerdictWatch;
    use shroud_surrogate::SurrogateWire;
    use shroud_surrogate::{fit_surrogate, FitOptions, Sides};

    #[test]
    fn a_verdict_names_bands_and_a_silent_guard_is_a_stop_without_numbers() {
        let mut watch = VerdictWatch::new(1_000);
        let empty = verdict_view("arm", &watch.shown(0));
        assert_eq!((empty.verdict.as_str(), empty.stop), ("no-verdict", true));
        assert_eq!((empty.min_clearance, empty.links.len()), (None, 0));
        let mut msg = collision(&[("wrist", 0.02, false), ("base", f64::INFINITY, false)]);
        msg.verdict = GuardVerdict::Stop;
        msg.min_clearance = 0.02;
        watch.on_verdict(msg, 0);
        let shown = verdict_view("arm", &watch.shown(500));
        assert_eq!((shown.verdict.as_str(), shown.stop), ("stop", true));
        assert_eq!(shown.min_clearance, Some(0.02));
        assert_eq!(shown.verdict_age_ms, Some(500.0 / 1e6));
        assert_eq!(shown.links[0].band, "stop");
        assert_eq!(shown.links[1].clearance, None);
        let json = serde_json::to_value(&shown).unwrap();
        assert_eq!(json["links"][1]["clearance"], serde_json::Value::Null);
        assert_eq!(json["min_clearance"], 0.02);
        assert_eq!(
            (json["speed_scale"].as_f64(), json["speed_state"].as_str()),
            (Some(0.0), Some("stopped"))
        );
        assert_eq!(empty.speed, "stopped (no-verdict)");
    }

    #[test]
    fn a_scaled_verdict_shows_its_scale_limiting_link_and_protective_distance() {
        let mut watch = VerdictWatch::new(1_000);
        let mut msg = collision(&[("forearm", 0.9, false)]);
        (msg.speed_scale, msg.limiting_link, msg.protective_distance) =
            (0.625, "forearm".into(), 0.84);
        watch.on_verdict(msg, 0);
        let json = serde_json::to_value(verdict_view("arm", &watch.shown(10))).unwrap();
        assert_eq!(json["speed_scale"], 0.625);
        assert_eq!(json["speed_state"], "scaled");
        assert_eq!(
            json["speed"],
            "62 % speed, limited by forearm (S_p 0.840 m)"
        );
        assert_eq!(json["limiting_link"], "forearm");
        assert_eq!(json["protective_distance"], 0.84);
        // Silent, the guard's last numbers are gone and the arm is stopped.
        let json = serde_json::to_value(verdict_view("arm", &watch.shown(5_000))).unwrap();
        assert_eq!(
            (json["verdict"].as_str(), json["speed_scale"].as_f64()),
            (Some("no-verdict"), Some(0.0))
        );
        assert_eq!(json["limiting_link"], serde_json::Value::Null);
        assert_eq!(json["protective_distance"], serde_json::Value::Null);
        assert_eq!(json["speed"], "stopped (no-verdict)");
    }

    #[test]
    fn certificates_are_keyed_by_side_and_status_gauges_are_finite_or_null() {
        let points: Vec<[f32; 3]> = (0..400)
            .map(|i| [(i % 20) as f32 * 0.1, (i / 20) as f32 * 0.1, 0.0])
            .collect();
        let options = FitOptions {
            cols: 4,
            rows: 4,
            sides: Sides::Upper,
            ..Default::default()
        };
        let s = fit_surrogate(&points, &options).unwrap();
        let msg = SurrogateMessage::from_surrogate(&s, 9, 3, "sim", 2_000_000);
        let view = certificate_view("flat", &msg);
        let upper = view.upper.clone().unwrap();
        assert_eq!((upper.side.as_str(), upper.points_checked), ("upper", 400));
        assert_eq!(upper.violations, 0);
        assert!(view.lower.is_none());
        assert_eq!((view.fit_ms, view.source_sequence), (2.0, 3));
        let json = serde_json::to_value(&view).unwrap();
        assert_eq!(json["upper"]["points_checked"], 400);
        let mut status = NodeStatusMessage::new("fit", "fit", 7);
        status.counters.insert("received".into(), 4);
        status.gauges.insert("fit_ms".into(), 1.5);
        status.gauges.insert("latency_ms".into(), f64::NAN);
        let view = status_view(&status);
        assert_eq!(view.counters["received"], 4);
        assert_eq!(view.gauges["fit_ms"], Some(1.5));
        assert_eq!(view.gauges["latency_ms"], None);
    }

    #[test]
    fn every_view_has_a_json_schema_naming_its_fields() {
        let schema = serde_json::to_value(schemars::schema_for!(VerdictView)).unwrap();
        assert!(schema["properties"]["min_clearance"].is_object());
        for field in [
            "speed_scale",
            "speed_state",
            "speed",
            "limiting_link",
            "protective_distance",
        ] {
            assert!(schema["properties"][field].is_object(), "{field}");
        }
        let schema = serde_json::to_value(schemars::schema_for!(CertificateView)).unwrap();
        assert!(schema["properties"]["upper"].is_object());
        let schema = serde_json::to_value(schemars::schema_for!(StatusView)).unwrap();
        assert!(schema["properties"]["counters"].is_object());
    }
}
