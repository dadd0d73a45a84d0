//! zenoh's admin-space metrics text (`ZenohDrops::from_openmetrics`, which
//! every node reads for its drop counts): only the dropped-message series
//! count, so the text reduced to them reads the same.

use shroud_graph::metrics::ZenohDrops;

pub fn run(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    let drops = ZenohDrops::from_openmetrics(&text);
    let dropped_lines: Vec<&str> = (text.lines())
        .filter(|l| l.contains("_network_message_dropped_payload_bytes_count"))
        .collect();
    assert_eq!(
        drops,
        ZenohDrops::from_openmetrics(&dropped_lines.join("\n")),
        "a line of another family changed the counts"
    );
}

/// A router's metrics with drops of each reason, as zenoh 1.10 (`stats`)
/// serves them.
pub fn seeds() -> Vec<Vec<u8>> {
    let text = r#"zenoh_build_info{local_id="a1",local_whatami="router",version="v1.10.2"} 1
zenoh_transports_opened{local_id="a1",local_whatami="router"} 3
rx_network_message_dropped_payload_bytes_count{local_id="a1",local_whatami="router",reason="access-control",space="user"} 7
rx_network_message_dropped_payload_bytes_sum{local_id="a1",local_whatami="router",reason="access-control",space="user"} 700
tx_network_message_dropped_payload_bytes_count{local_id="a1",local_whatami="router",reason="congestion",priority="data"} 5
# EOF
"#;
    vec![text.as_bytes().to_vec()]
}
