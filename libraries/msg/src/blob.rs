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
    decode_floats(bytes, field, f32::from_le_bytes, f32::is_finite)
}

/// Decodes a blob of `f64` values, checking its length and finiteness.
pub fn bytes_to_f64s(bytes: &[u8], field: &'static str) -> Result<Vec<f64>, MessageError> {
    decode_floats(bytes, field, f64::from_le_bytes, f64::is_finite)
}

/// The shared decoder: `N`-byte little-endian values, all finite.
fn decode_floats<T, const N: usize>(
    bytes: &[u8],
    field: &'static str,
    from_le: fn([u8; N]) -> T,
    is_finite: fn(T) -> bool,
) -> Result<Vec<T>, MessageError>
where
    T: Copy,
{
    let (chunks, rest) = bytes.as_chunks::<N>();
    if !rest.is_empty() {
        return Err(MessageError::BlobLength {
            field,
            len: bytes.len(),
            unit: N,
        });
    }
    let values: Vec<T> = chunks.iter().map(|c| from_le(*c)).collect();
    match values.iter().position(|&v| !is_finite(v)) {
        Some(index) => Err(MessageError::NonFinite { field, index }),
        None => Ok(values),
    }
}

pub fn encode<T: serde::Serialize>(value: &T) -> Result<Vec<u8>, MessageError> {
    rmp_serde::to_vec_named(value).map_err(|e| MessageError::Malformed(e.to_string()))
}

/// The length of `value`'s encoding, without writing it (to size a buffer that
/// the message is then encoded into, such as a shared-memory segment).
pub fn encoded_len<T: serde::Serialize>(value: &T) -> Result<usize, MessageError> {
    let mut counter = ByteCounter(0);
    rmp_serde::encode::write_named(&mut counter, value)
        .map_err(|e| MessageError::Malformed(e.to_string()))?;
    Ok(counter.0)
}

/// Encodes `value` into `out`, which must be exactly [`encoded_len`] long.
pub fn encode_into<T: serde::Serialize>(value: &T, out: &mut [u8]) -> Result<(), MessageError> {
    let len = out.len();
    let mut rest = &mut out[..];
    rmp_serde::encode::write_named(&mut rest, value)
        .map_err(|e| MessageError::Malformed(e.to_string()))?;
    if rest.is_empty() {
        Ok(())
    } else {
        Err(MessageError::Malformed(format!(
            "encoding is {} bytes, the buffer {len}",
            len - rest.len()
        )))
    }
}

/// A writer that only counts.
struct ByteCounter(usize);

impl std::io::Write for ByteCounter {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.0 += buf.len();
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

pub fn decode<'a, T: serde::Deserialize<'a>>(bytes: &'a [u8]) -> Result<T, MessageError> {
    rmp_serde::from_slice(bytes).map_err(|e| MessageError::Malformed(e.to_string()))
}
