//! shroud's CAN range-sensor protocol (`CanScanDecoder`, docs/sensor-protocols.md §2):
//! frames in, scans out. A decoded scan, encoded again, decodes the same.

use crate::can_records::{record, records};
use crate::check::{named, same};
use shroud_drivers::can::{CanScanDecoder, CanSensorConfig};
use shroud_drivers::Scan;

pub fn run(data: &[u8]) {
    let config = CanSensorConfig::default();
    let mut decoder = CanScanDecoder::new(config);
    let mut results = Vec::new();
    for r in records(data) {
        results.extend(decoder.push(&r.frame));
    }
    results.extend(decoder.finish());
    for result in results {
        match result {
            Ok(scan) => {
                let again = decode(&config, &scan);
                same(&vec![scan], &again, "scans after a round trip");
            }
            Err(e) => named(&e),
        }
    }
}

fn decode(config: &CanSensorConfig, scan: &Scan) -> Vec<Scan> {
    let frames = config.encode(scan).expect("a decoded scan encodes");
    let mut decoder = CanScanDecoder::new(*config);
    let mut out: Vec<_> = frames.iter().flat_map(|f| decoder.push(f)).collect();
    out.extend(decoder.finish());
    out.into_iter()
        .map(|r| r.expect("an encoded scan decodes"))
        .collect()
}

pub fn seeds() -> Vec<Vec<u8>> {
    let config = CanSensorConfig::default();
    let scan = Scan::new(
        5,
        1_700_000_000_000_000_000,
        vec![[1.0, -2.0, 0.5], [0.25, 0.0, 3.0]],
    );
    let frames = config.encode(&scan).expect("the seed scan encodes");
    vec![frames.iter().flat_map(|f| record(f, 1)).collect()]
}
