//! The launcher's live one-line summary of a running graph: rates, latency,
//! certificate and clearance, folded from the messages the graph publishes.

use crate::message::{CollisionMessage, NodeStatusMessage, SurrogateMessage};
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

    /// A surrogate arrived at `received_ns` (same clock as its source stamp).
    pub fn on_surrogate(&mut self, msg: &SurrogateMessage, received_ns: u64) {
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
        self.last_latency_ms = Some(received_ns.saturating_sub(msg.source_stamp_ns) as f64 / 1e6);
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
            let mut part = format!("{name}: {} out", s.counter("published"));
            if let Some(p50) = s.gauge("fit_p50_ms") {
                part += &format!(", fit p50 {p50:.2} ms");
            }
            if let (Some(p50), Some(p99)) = (s.gauge("latency_p50_ms"), s.gauge("latency_p99_ms")) {
                part += &format!(", latency p50 {p50:.2} p99 {p99:.2} ms");
            }
            if let Some(ms) = s.gauge("blend_ms") {
                part += &format!(", last blend {ms:.0} ms");
            }
            let drops = s.counter("dropped_backlog") + s.counter("dropped_malformed");
            if drops > 0 {
                part += &format!(", {drops} dropped");
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
            parts.push(format!(
                "{}: {} clearance {:.3} m ({}), {} stops",
                c.arm,
                format!("{:?}", c.verdict).to_uppercase(),
                c.min_clearance,
                c.closest_link,
                self.stops
            ));
        }
        parts.join(" | ")
    }
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
}
