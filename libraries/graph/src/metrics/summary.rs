//! The launcher's live one-line summary of a running graph: rates, latency,
//! certificate and clearance, folded from the messages the graph publishes.

use super::names;
use shroud_msg::{CollisionMessage, GuardVerdict, NodeStatusMessage, SurrogateMessage};
use std::collections::BTreeMap;

/// Latest known state of the graph.
#[derive(Debug, Default, Clone)]
pub struct GraphSummary {
    statuses: BTreeMap<String, NodeStatusMessage>,
    surrogates: u64,
    last_certificate: Option<(u64, u64)>,
    last_latency_ms: Option<f64>,
    collision: Option<CollisionMessage>,
    stops: u64,
}

impl GraphSummary {
    pub fn on_status(&mut self, msg: NodeStatusMessage) {
        self.statuses.insert(msg.node.clone(), msg);
    }

    /// A surrogate arrived. Its latency is the pipeline delay the nodes
    /// measured on their own clocks (receipt of the cloud to publication).
    pub fn on_surrogate(&mut self, msg: &SurrogateMessage) {
        self.surrogates += 1;
        // Each surface of a sandwich certifies the same points.
        let checked = msg
            .surfaces
            .iter()
            .map(|s| s.certificate.points_checked)
            .max()
            .unwrap_or(0);
        let violations = msg.surfaces.iter().map(|s| s.certificate.violations).sum();
        self.last_certificate = Some((checked, violations));
        self.last_latency_ms = Some(msg.pipeline_ns as f64 / 1e6);
    }

    pub fn on_collision(&mut self, msg: CollisionMessage) {
        if msg.stop {
            self.stops += 1;
        }
        self.collision = Some(msg);
    }

    /// Surrogates seen so far.
    pub fn surrogates(&self) -> u64 {
        self.surrogates
    }

    /// One line: every node's publish rate, the fitter's timing, the latest
    /// certificate, and the guard's verdict.
    pub fn line(&self, elapsed_s: f64) -> String {
        let mut parts = vec![format!("t={elapsed_s:6.1}s")];
        for (name, s) in &self.statuses {
            let mut part = format!("{name}: {} out", s.counter(names::PUBLISHED.name));
            if let Some(p50) = s.gauge(names::FIT_P50_MS.name) {
                part += &format!(", fit p50 {p50:.2} ms");
            }
            if let (Some(p50), Some(p99)) = (
                s.gauge(names::LATENCY_P50_MS.name),
                s.gauge(names::LATENCY_P99_MS.name),
            ) {
                part += &format!(", latency p50 {p50:.2} p99 {p99:.2} ms");
            }
            if let Some(ms) = s.gauge(names::BLEND_MS.name) {
                part += &format!(", last blend {ms:.0} ms");
            }
            let drops =
                s.counter(names::DROPPED_BACKLOG.name) + s.counter(names::DROPPED_MALFORMED.name);
            if drops > 0 {
                part += &format!(", {drops} dropped");
            }
            if s.kind == crate::launch::NodeKind::Arm.as_str() {
                part += &arm_state(s);
            }
            parts.push(part);
        }
        match self.last_certificate {
            Some((checked, violations)) => {
                parts.push(format!("certified {checked} pts, {violations} violations"))
            }
            None => parts.push("no surrogate yet".into()),
        }
        if let Some(c) = &self.collision {
            let mut part = format!(
                "{}: {} clearance {:.3} m ({})",
                c.arm,
                c.verdict.name().to_uppercase(),
                c.min_clearance,
                c.closest_link,
            );
            if !c.stop && c.speed_scale < 1.0 {
                // Rounded down, as the viewers do: a slowed arm never reads 100 %.
                let percent = (100.0 * c.speed_scale).floor().clamp(0.0, 99.0);
                part += &format!(", {percent:.0} % speed");
                if !c.limiting_link.is_empty() {
                    part += &format!(
                        " ({} at S_p {:.3} m)",
                        c.limiting_link, c.protective_distance
                    );
                }
            }
            if c.stop && !c.reason.is_empty() {
                part += &format!(" [{}]", c.reason);
            }
            part += &format!(", {} stop verdicts", self.stops);
            parts.push(part);
        }
        parts.join(" | ")
    }
}

/// A simulated arm's motion: moving or halted (by what, for how long), and
/// the share of its life spent halted, from its status gauges and counters.
fn arm_state(s: &NodeStatusMessage) -> String {
    let halted_s = s.gauge(names::HALTED_S.name).unwrap_or(0.0);
    let share = if s.uptime_s > 0.0 {
        100.0 * halted_s / s.uptime_s
    } else {
        0.0
    };
    let causes: Vec<String> = GuardVerdict::ALL
        .iter()
        .filter(|v| s.counter(v.halt_counter()) > 0)
        .map(|v| format!("{} {}", s.counter(v.halt_counter()), v.name()))
        .collect();
    let state = if s.gauge(names::HALTED.name).unwrap_or(0.0) > 0.0 {
        format!(
            "HALTED for {:.1} s",
            s.gauge(names::HALT_CURRENT_S.name).unwrap_or(0.0)
        )
    } else {
        "moving".to_owned()
    };
    format!(
        ", {state}, halted {share:.0}% of {:.0} s ({} halts{}{})",
        s.uptime_s,
        s.counter(names::HALTS.name),
        if causes.is_empty() { "" } else { ": " },
        causes.join(", ")
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn folds_statuses_into_one_line() {
        let mut g = GraphSummary::default();
        assert!(g.line(0.0).contains("no surrogate yet"));
        let mut s = NodeStatusMessage::new("fit", "fit", 1);
        s.counters.insert("published".into(), 12);
        s.counters.insert("dropped_backlog".into(), 2);
        s.gauges.insert("fit_p50_ms".into(), 2.5);
        g.on_status(s);
        let line = g.line(3.0);
        assert!(
            line.contains("fit: 12 out, fit p50 2.50 ms, 2 dropped"),
            "{line}"
        );
    }

    #[test]
    fn a_scaled_clear_says_how_fast_and_which_link_limits_it() {
        let mut g = GraphSummary::default();
        let mut c = shroud_msg::sample_collision(shroud_msg::GuardVerdict::Clear);
        g.on_collision(c.clone());
        assert!(!g.line(1.0).contains("% speed"), "{}", g.line(1.0));
        c.speed_scale = 0.625;
        c.limiting_link = "forearm".into();
        c.protective_distance = 0.84;
        g.on_collision(c);
        let line = g.line(1.0);
        assert!(
            line.contains("CLEAR clearance 0.200 m (wrist), 62 % speed (forearm at S_p 0.840 m)"),
            "{line}"
        );
    }

    #[test]
    fn an_arm_says_whether_it_moves_and_what_halted_it() {
        let mut g = GraphSummary::default();
        let mut arm = NodeStatusMessage::new("arm", "arm", 1);
        arm.uptime_s = 10.0;
        arm.counters.insert("halts".into(), 3);
        arm.counters.insert("halts_stop".into(), 2);
        arm.counters.insert("halts_no_verdict".into(), 1);
        arm.gauges.insert("halted_s".into(), 2.5);
        arm.gauges.insert("halted".into(), 0.0);
        g.on_status(arm.clone());
        let line = g.line(10.0);
        assert!(
            line.contains("moving, halted 25% of 10 s (3 halts: 2 stop, 1 no-verdict)"),
            "{line}"
        );
        arm.gauges.insert("halted".into(), 1.0);
        arm.gauges.insert("halt_current_s".into(), 0.75);
        g.on_status(arm);
        assert!(
            g.line(10.0).contains("HALTED for 0.8 s"),
            "{}",
            g.line(10.0)
        );
    }
}
