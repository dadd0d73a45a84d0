//! Legacy express scan (answer type 0x82): 16 cabins of two samples each in
//! an 84-byte capsule (`sl_lidar_response_cabin_nodes_t`; protocol PDF
//! Figure 4-13; decoding as `_onScanNodeCapsuleData` in
//! `handler_capsules.cpp`).
//!
//! ```text
//! cabin (5 bytes): distance_angle_1 u16 LE, distance_angle_2 u16 LE, offset_angles_q3 u8
//! distance_k (q2 mm) = distance_angle_k & 0xFFFC      (so mm = raw >> 2)
//! dθ_1 (q3 deg) = (offset & 0x0F) | (distance_angle_1 & 3) << 4
//! dθ_2 (q3 deg) = (offset >> 4)   | (distance_angle_2 & 3) << 4
//! sample k = 0..31: raw angle = start + span · k / 32; heading = raw − dθ_k
//! ```
//! dθ is taken as an unsigned 6-bit value and subtracted, as the SDK does;
//! the PDF calls its top bit a sign bit, but following it rotates points by
//! about 12° (`Roboticia/RPLidar` PR #4; research notes §1.2).

use super::capsule::{Capsule, CapsuleLayout, RawSample};

/// Bytes before the first cabin (checksum nibbles, start angle).
const CABINS_AT: usize = 4;
const CABIN_LEN: usize = 5;

/// The legacy express layout.
#[derive(Debug, Clone, Copy)]
pub struct ExpressLayout;

impl CapsuleLayout for ExpressLayout {
    const SAMPLES: usize = 32;

    fn decode(capsule: &Capsule, start_q16: i64, span_q8: i64, out: &mut Vec<RawSample>) {
        // SDK: angleInc_q16 = diffAngle_q8 << 3, i.e. span / 32 in q16.
        let step_q16 = span_q8 << 3;
        let cabins = capsule.get(CABINS_AT..).unwrap_or_default();
        for cabin in cabins.chunks_exact(CABIN_LEN) {
            let [a0, a1, b0, b1, offsets] = <[u8; CABIN_LEN]>::try_from(cabin).unwrap_or_default();
            let first = u16::from_le_bytes([a0, a1]);
            let second = u16::from_le_bytes([b0, b1]);
            let offset_first = (offsets & 0x0F) | ((first & 3) << 4) as u8;
            let offset_second = (offsets >> 4) | ((second & 3) << 4) as u8;
            for (distance_angle, offset_q3) in [(first, offset_first), (second, offset_second)] {
                let raw_q16 = start_q16 + step_q16 * out.len() as i64;
                out.push(RawSample {
                    raw_q16,
                    // q3 → q16: shift by 13.
                    heading_q16: raw_q16 - (i64::from(offset_q3) << 13),
                    distance_q2: u32::from(distance_angle & 0xFFFC),
                });
            }
        }
    }
}
