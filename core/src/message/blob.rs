//! Little-endian byte blobs for bulk arrays (f32 points, f64 coefficients).

use super::error::MessageError;

pub fn f32s_to_bytes(values: impl Iterator<Item = f32>) -> Vec<u8> {
    values.flat_map(f32::to_le_bytes).collect()
}

pub fn f64s_to_bytes(values: &[f64]) -> Vec<u8> {
    values.iter().flat_map(|v| v.to_le_bytes()).collect()
}

/// Decodes a blob of `f32` values, checking its length and finiteness.
pub fn bytes_to_f32s(bytes: &[u8], field: &'static str) -> Result<Vec<f32>, MessageError> {
    if !bytes.len().is_multiple_of(4) {
        return Err(MessageError::BlobLength {
            field,
            len: bytes.len(),
            unit: 4,
        });
    }
    let values: Vec<f32> = bytes
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    match values.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(MessageError::NonFinite { field, index }),
        None => Ok(values),
    }
}

/// Decodes a blob of `f64` values, checking its length and finiteness.
pub fn bytes_to_f64s(bytes: &[u8], field: &'static str) -> Result<Vec<f64>, MessageError> {
    if !bytes.len().is_multiple_of(8) {
        return Err(MessageError::BlobLength {
            field,
            len: bytes.len(),
            unit: 8,
        });
    }
    let values: Vec<f64> = bytes
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]))
        .collect();
    match values.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(MessageError::NonFinite { field, index }),
        None => Ok(values),
    }
}

pub fn encode<T: serde::Serialize>(value: &T) -> Result<Vec<u8>, MessageError> {
    rmp_serde::to_vec_named(value).map_err(|e| MessageError::Malformed(e.to_string()))
}

pub fn decode<'a, T: serde::Deserialize<'a>>(bytes: &'a [u8]) -> Result<T, MessageError> {
    rmp_serde::from_slice(bytes).map_err(|e| MessageError::Malformed(e.to_string()))
}
