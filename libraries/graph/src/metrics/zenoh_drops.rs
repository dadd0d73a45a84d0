//! What zenoh itself dropped in a process, read from the OpenMetrics text its
//! admin space serves (`@/<zid>/<whatami>/metrics`, zenoh 1.10 built with
//! `stats`): messages refused by access control, and messages a congested
//! link dropped, which zenoh's `put` does not report to its caller.

use super::names::{self, Counter};

/// Messages zenoh dropped in one session, by reason, both directions.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ZenohDrops {
    /// Refused by access control (`reason="access-control"`).
    pub access_control: u64,
    /// Dropped by a congested link (`reason="congestion"`).
    pub congestion: u64,
    /// Any other reason (downsampling, low-pass, no link).
    pub other: u64,
}

/// The family zenoh-stats counts dropped messages in: a histogram of their
/// payload sizes per direction, whose `_count` series counts the messages.
const DROPPED_COUNT: &str = "_network_message_dropped_payload_bytes_count";

impl ZenohDrops {
    /// The counts a status message carries, by counter.
    pub fn counters(&self) -> [(Counter, u64); 2] {
        [
            (names::ZENOH_DROPPED_ACCESS_CONTROL, self.access_control),
            (names::ZENOH_DROPPED_CONGESTION, self.congestion),
        ]
    }

    /// Sums the dropped-message counts of an OpenMetrics text by reason;
    /// lines of other families, comments and malformed lines are skipped.
    pub fn from_openmetrics(text: &str) -> Self {
        let mut drops = Self::default();
        for line in text.lines().filter(|l| !l.starts_with('#')) {
            let Some((series, value)) = line.rsplit_once(' ') else {
                continue;
            };
            let name = series.split('{').next().unwrap_or("");
            let Some(count) = value.trim().parse::<f64>().ok().filter(|v| *v >= 0.0) else {
                continue;
            };
            if !name.ends_with(DROPPED_COUNT) {
                continue;
            }
            let slot = match label(series, "reason") {
                Some("access-control") => &mut drops.access_control,
                Some("congestion") => &mut drops.congestion,
                _ => &mut drops.other,
            };
            *slot = slot.saturating_add(count as u64);
        }
        drops
    }
}

/// The value of label `name` in `family{a="x",name="y"}` (label values
/// here are names and numbers: no escaped quotes or commas).
fn label<'a>(series: &'a str, name: &str) -> Option<&'a str> {
    let labels = series.split_once('{')?.1.strip_suffix('}')?;
    labels.split(',').find_map(|pair| {
        let (key, value) = pair.split_once('=')?;
        (key.trim() == name).then(|| value.trim().trim_matches('"'))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_dropped_messages_by_reason_in_both_directions() {
        let text = r#"# TYPE rx_network_message_dropped_payload_bytes histogram
zenoh_transports_opened{local_id="a",local_whatami="router"} 3
rx_network_message_dropped_payload_bytes_count{local_id="a",local_whatami="router",reason="access-control",space="user"} 7
rx_network_message_dropped_payload_bytes_sum{local_id="a",local_whatami="router",reason="access-control",space="user"} 700
tx_network_message_dropped_payload_bytes_count{local_id="a",local_whatami="router",reason="access-control",space="user"} 2
tx_network_message_dropped_payload_bytes_count{local_id="a",local_whatami="router",reason="congestion",priority="data"} 5
tx_network_message_dropped_payload_bytes_count{local_id="a",reason="no-link"} 1
tx_network_message_dropped_payload_bytes_count{local_id="a",xreason="congestion",reason="low-pass"} 1
tx_network_message_dropped_payload_bytes_count{local_id="a",reason="congestion"} not-a-number
# EOF"#;
        let drops = ZenohDrops::from_openmetrics(text);
        assert_eq!(
            drops,
            ZenohDrops {
                access_control: 9,
                congestion: 5,
                other: 2
            }
        );
        assert_eq!(ZenohDrops::from_openmetrics(""), ZenohDrops::default());
    }

    proptest::proptest! {
        /// Any text reads without a panic, and only the dropped-message
        /// series count: other lines around them change nothing.
        #[test]
        fn only_dropped_series_count(noise in "\\PC{0,200}", count in 0u32..1000) {
            let series = format!(
                "tx_network_message_dropped_payload_bytes_count{{reason=\"congestion\"}} {count}"
            );
            let noise = noise.replace('\n', " ").replace("dropped_payload", "x");
            let text = format!("{noise}\n{series}\n{noise}");
            let drops = ZenohDrops::from_openmetrics(&text);
            proptest::prop_assert_eq!(drops.congestion, u64::from(count));
            proptest::prop_assert_eq!(drops.access_control + drops.other, 0);
        }
    }
}
