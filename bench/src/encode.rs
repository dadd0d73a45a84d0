//! The last step the device benches time: a finished scan encoded as the
//! sensor nodes encode it (`Scan::to_view`, `PayloadWriter::encode`, copy
//! path), from the call that finished it.

use anyhow::Result;
use shroud_drivers::Scan;
use shroud_msg::SensorPose;
use shroud_nodes::transport::PayloadWriter;
use std::hint::black_box;
use std::time::Instant;

/// Encodes `scan` as cloud `sequence` of `source`, its pipeline time counted
/// from `start`, and records the microseconds from `start` to the encoding.
pub fn encode_timed(
    scan: &Scan,
    source: &str,
    sequence: u64,
    start: Instant,
    writer: &PayloadWriter,
    into: &mut Vec<f64>,
) -> Result<()> {
    let view = scan
        .to_view(sequence, source, SensorPose::default())?
        .with_pipeline_ns(start.elapsed().as_nanos() as u64);
    black_box(writer.encode(&view)?);
    into.push(start.elapsed().as_secs_f64() * 1e6);
    Ok(())
}
