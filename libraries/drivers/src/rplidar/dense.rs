//! Dense capsules (answer type 0x85, e.g. S1/C1 "DenseBoost"): 40 distances
//! in an 84-byte capsule (`sl_lidar_response_dense_capsule_measurement_nodes_t`;
//! decoding as `_onScanNodeDenseCapsuleData` in `handler_capsules.cpp`).
//!
//! ```text
//! b4..83: 40 × distance u16 LE, millimetres (0 = no return)
//! sample k = 0..39: heading = start + span · k / 40   (no per-sample correction)
//! ```
//! The SDK drops a capsule whose span is wider than 40 samples could cover at
//! 100 revolutions a second (`maxDiffAngleThreshold_q8`); so does this
//! decoder, as a loss counted `capsule_gap`. (The SDK stamps a dense capsule's
//! samples from the arrival of the capsule after it; this decoder uses the
//! capsule's own arrival, as the SDK does for express capsules.)

use super::capsule::{Capsule, CapsuleLayout, RawSample};
use super::timing::SampleClock;

const DISTANCES_AT: usize = 4;
/// Fastest rotation the span check allows, revolutions a second.
const MAX_ROTATION_HZ: u64 = 100;

/// The dense layout.
#[derive(Debug, Clone, Copy)]
pub struct DenseLayout;

impl CapsuleLayout for DenseLayout {
    const SAMPLES: usize = 40;

    fn decode(capsule: &Capsule, start_q16: i64, span_q8: i64, out: &mut Vec<RawSample>) {
        // SDK: angleInc_q16 = (diffAngle_q8 << 8) / 40 (truncating).
        let step_q16 = (span_q8 << 8) / Self::SAMPLES as i64;
        let distances = capsule.get(DISTANCES_AT..).unwrap_or_default();
        for pair in distances.chunks_exact(2) {
            let [lo, hi] = <[u8; 2]>::try_from(pair).unwrap_or_default();
            let raw_q16 = start_q16 + step_q16 * out.len() as i64;
            out.push(RawSample {
                raw_q16,
                heading_q16: raw_q16,
                distance_q2: u32::from(u16::from_le_bytes([lo, hi])) << 2,
            });
        }
    }

    fn span_plausible(span_q8: i64, clock: &SampleClock) -> bool {
        let sample_ns = clock.sample_ns();
        if sample_ns == 0 {
            return true;
        }
        // 360° × 100 Hz × 40 samples × sample duration, in q8 degrees.
        let max_q8 = (360 * MAX_ROTATION_HZ * Self::SAMPLES as u64 * 256).saturating_mul(sample_ns)
            / 1_000_000_000;
        u64::try_from(span_q8).is_ok_and(|span| span <= max_q8)
    }
}
