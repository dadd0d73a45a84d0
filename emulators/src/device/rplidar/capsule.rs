//! Encodes express capsules, legacy (answer type 0x82) and dense (0x85), and
//! computes the sample angles a host decoder derives from them.
//!
//! Both are 84 bytes: `0xA<<4 | chk[3:0]`, `0x5<<4 | chk[7:4]`, the start
//! angle u16 LE (bit 15 = S "new scan", bits 0..14 = q6 degrees), then 80
//! bytes of samples; `chk` is the XOR of bytes 2..84. Legacy capsules hold 16
//! cabins of `distance_angle_1 u16, distance_angle_2 u16, offset_angles_q3
//! u8` (32 samples), dense ones 40 u16 LE distances in mm
//! (`sl_lidar_cmd.h`, `sl_lidar_response_capsule_measurement_nodes_t` and
//! `sl_lidar_response_dense_capsule_measurement_nodes_t`).
//!
//! A decoder places sample k of a capsule by interpolating from this
//! capsule's start angle to the next one's, then (legacy only) subtracting
//! the sample's unsigned 6-bit dθ in q3 degrees (`handler_capsules.cpp`,
//! `_onScanNodeCapsuleData()` and `_onScanNodeDenseCapsuleData()`).
//! [`decoded_angle_q6`] is that computation, in the SDK's fixed point.

use super::protocol::FULL_TURN_Q6;

/// Bytes in a capsule of either kind.
pub(crate) const CAPSULE_LEN: usize = 84;
/// Samples in a legacy capsule.
pub(crate) const LEGACY_SAMPLES: usize = 32;
/// Samples in a dense capsule.
pub(crate) const DENSE_SAMPLES: usize = 40;
/// Largest dθ a legacy sample can carry (6 bits, q3 degrees).
pub(crate) const MAX_DTHETA_Q3: u8 = 63;
/// Largest distance a legacy sample can carry (14 bits, mm).
pub(crate) const MAX_LEGACY_MM: u16 = 0x3FFF;

const SYNC_1: u8 = 0xA0;
const SYNC_2: u8 = 0x50;
const NEW_SCAN: u16 = 0x8000;

/// One legacy-capsule sample.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct LegacySample {
    /// Millimetres, at most [`MAX_LEGACY_MM`]; 0 = no measurement.
    pub distance_mm: u16,
    /// Angle offset in q3 degrees, at most [`MAX_DTHETA_Q3`].
    pub dtheta_q3: u8,
}

/// A legacy capsule. Sample 2j and 2j+1 fill cabin j: their distances sit in
/// bits 2..15 of the two u16s, dθ bits 4..5 in bits 0..1 of those u16s, dθ
/// bits 0..3 in the low (first) and high (second) nibble of the offset byte.
pub(crate) fn legacy(
    start_q6: u16,
    new_scan: bool,
    samples: &[LegacySample; LEGACY_SAMPLES],
) -> [u8; CAPSULE_LEN] {
    let mut capsule = header(start_q6, new_scan);
    for (cabin, pair) in capsule[4..]
        .chunks_exact_mut(5)
        .zip(samples.chunks_exact(2))
    {
        if let [first, second] = pair {
            let [a0, a1] = cabin_word(*first).to_le_bytes();
            let [b0, b1] = cabin_word(*second).to_le_bytes();
            let offsets = (first.dtheta_q3 & 0x0F) | ((second.dtheta_q3 & 0x0F) << 4);
            cabin.copy_from_slice(&[a0, a1, b0, b1, offsets]);
        }
    }
    seal(&mut capsule);
    capsule
}

fn cabin_word(sample: LegacySample) -> u16 {
    let distance = sample.distance_mm.min(MAX_LEGACY_MM) << 2;
    distance | u16::from((sample.dtheta_q3 >> 4) & 0x03)
}

/// A dense capsule of 40 distances in mm.
pub(crate) fn dense(
    start_q6: u16,
    new_scan: bool,
    distances_mm: &[u16; DENSE_SAMPLES],
) -> [u8; CAPSULE_LEN] {
    let mut capsule = header(start_q6, new_scan);
    for (slot, distance) in capsule[4..].chunks_exact_mut(2).zip(distances_mm) {
        slot.copy_from_slice(&distance.to_le_bytes());
    }
    seal(&mut capsule);
    capsule
}

fn header(start_q6: u16, new_scan: bool) -> [u8; CAPSULE_LEN] {
    let mut capsule = [0u8; CAPSULE_LEN];
    let flag = if new_scan { NEW_SCAN } else { 0 };
    let [s0, s1] = ((start_q6 & 0x7FFF) | flag).to_le_bytes();
    capsule[2] = s0;
    capsule[3] = s1;
    capsule
}

/// Writes the checksum nibbles and sync nibbles into bytes 0 and 1.
fn seal(capsule: &mut [u8; CAPSULE_LEN]) {
    let checksum = capsule[2..].iter().fold(0u8, |acc, byte| acc ^ byte);
    capsule[0] = SYNC_1 | (checksum & 0x0F);
    capsule[1] = SYNC_2 | (checksum >> 4);
}

/// Damages a sealed capsule's checksum (sync nibbles untouched, so a decoder
/// still frames it and then rejects it).
pub(crate) fn break_checksum(capsule: &mut [u8; CAPSULE_LEN]) {
    capsule[0] ^= 0x01;
}

/// The decoder's angle of sample `index` of a capsule holding `count`
/// samples, before the dθ correction, in q16 degrees: the start angle plus
/// `index` × (angle to the next capsule's start, wrapped into [0, 360°)) /
/// `count`, in the SDK's integer steps (`diff_q8 << 8 / count`).
pub(crate) fn interpolated_q16(
    start_q6: u16,
    next_start_q6: u16,
    index: usize,
    count: usize,
) -> i64 {
    let start = i64::from(start_q6 & 0x7FFF);
    let diff_q6 = (i64::from(next_start_q6 & 0x7FFF) - start).rem_euclid(FULL_TURN_Q6);
    let count = i64::try_from(count.max(1)).unwrap_or(i64::MAX);
    let index = i64::try_from(index).unwrap_or(0);
    let step_q16 = ((diff_q6 << 2) << 8) / count;
    (start << 10) + index * step_q16
}

/// The q6 angle a decoder reports for a sample whose interpolated angle is
/// `interpolated_q16` and whose dθ is `dtheta_q3` (0 for dense capsules):
/// `(interpolated − dθ << 13) >> 10`, wrapped into [0, 360°).
pub(crate) fn decoded_angle_q6(interpolated_q16: i64, dtheta_q3: u8) -> u16 {
    let q6 = (interpolated_q16 - (i64::from(dtheta_q3) << 13)) >> 10;
    u16::try_from(q6.rem_euclid(FULL_TURN_Q6)).unwrap_or(0)
}
