//! The frame layout: `u32` header length, the JSON header, spaces to a 4-byte
//! boundary, then each array padded to a 4-byte boundary (docs/dashboard-protocol.md). Arrays
//! are little-endian so that a browser (little-endian on every platform it runs
//! on) views them with `Float32Array(buffer, offset, count)`.

use super::error::DashboardError;
use serde_json::{Map, Value};

/// One array's elements.
#[derive(Debug, Clone, PartialEq)]
pub enum ArrayData {
    F32(Vec<f32>),
    U32(Vec<u32>),
    U8(Vec<u8>),
}

impl ArrayData {
    fn type_name(&self) -> &'static str {
        match self {
            Self::F32(_) => "f32",
            Self::U32(_) => "u32",
            Self::U8(_) => "u8",
        }
    }

    fn count(&self) -> usize {
        match self {
            Self::F32(v) => v.len(),
            Self::U32(v) => v.len(),
            Self::U8(v) => v.len(),
        }
    }

    fn write(&self, out: &mut Vec<u8>) {
        match self {
            Self::F32(v) => out.extend(v.iter().flat_map(|x| x.to_le_bytes())),
            Self::U32(v) => out.extend(v.iter().flat_map(|x| x.to_le_bytes())),
            Self::U8(v) => out.extend_from_slice(v),
        }
    }
}

/// A frame under construction: header fields and arrays.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    header: Map<String, Value>,
    arrays: Vec<(String, ArrayData)>,
}

impl Frame {
    /// A frame of this `type`.
    pub fn new(kind: &str) -> Self {
        let mut header = Map::new();
        header.insert("type".into(), Value::from(kind));
        Self {
            header,
            arrays: Vec::new(),
        }
    }

    /// Sets a header field.
    pub fn field(mut self, key: &str, value: impl Into<Value>) -> Self {
        self.header.insert(key.into(), value.into());
        self
    }

    /// Appends an array.
    pub fn array(mut self, name: &str, data: ArrayData) -> Self {
        self.arrays.push((name.into(), data));
        self
    }

    /// The frame's bytes.
    pub fn encode(self) -> Vec<u8> {
        let Self { mut header, arrays } = self;
        let listed: Vec<Value> = arrays
            .iter()
            .map(|(name, data)| {
                serde_json::json!({"name": name, "type": data.type_name(), "count": data.count()})
            })
            .collect();
        header.insert("arrays".into(), Value::Array(listed));
        let text = Value::Object(header).to_string();
        let payload: usize = arrays.iter().map(|(_, d)| padded(byte_len(d))).sum();
        let mut out = Vec::with_capacity(4 + padded(text.len()) + payload);
        // A header longer than 4 GiB cannot be built from the messages the
        // node handles (names are at most 64 bytes, lists are bounded).
        out.extend_from_slice(&(text.len() as u32).to_le_bytes());
        out.extend_from_slice(text.as_bytes());
        pad(&mut out, b' ');
        for (_, data) in &arrays {
            data.write(&mut out);
            pad(&mut out, 0);
        }
        out
    }
}

fn byte_len(data: &ArrayData) -> usize {
    match data {
        ArrayData::U8(v) => v.len(),
        other => 4 * other.count(),
    }
}

fn padded(len: usize) -> usize {
    len.next_multiple_of(4)
}

fn pad(out: &mut Vec<u8>, byte: u8) {
    out.resize(padded(out.len()), byte);
}

/// A decoded frame: its header and where each array lies.
#[derive(Debug, Clone, PartialEq)]
pub struct DecodedFrame {
    pub header: Map<String, Value>,
    pub arrays: Vec<DecodedArray>,
}

/// One array of a decoded frame.
#[derive(Debug, Clone, PartialEq)]
pub struct DecodedArray {
    pub name: String,
    pub kind: String,
    pub count: usize,
    /// Byte offset of its first element in the frame.
    pub offset: usize,
}

impl DecodedFrame {
    /// Reads a frame as a browser does, checking every length against the
    /// frame's size before using it (a test client and the fuzzer use this).
    pub fn decode(bytes: &[u8]) -> Result<Self, DashboardError> {
        let truncated = |what: &str, needed: usize, offset: usize| DashboardError::Truncated {
            what: what.into(),
            needed,
            offset,
            len: bytes.len(),
        };
        let head: [u8; 4] = bytes
            .get(..4)
            .and_then(|b| b.try_into().ok())
            .ok_or_else(|| truncated("the header length", 4, 0))?;
        let header_len = u32::from_le_bytes(head) as usize;
        let text = bytes
            .get(4..4usize.saturating_add(header_len))
            .ok_or_else(|| truncated("the header", header_len, 4))?;
        let header: Map<String, Value> =
            serde_json::from_slice(text).map_err(|e| DashboardError::Header(e.to_string()))?;
        if !header.get("type").is_some_and(Value::is_string) {
            return Err(DashboardError::Header("no string \"type\"".into()));
        }
        let listed = header
            .get("arrays")
            .and_then(Value::as_array)
            .ok_or_else(|| DashboardError::Header("no \"arrays\" list".into()))?;
        let mut offset = padded(4 + header_len);
        let mut arrays = Vec::with_capacity(listed.len().min(64));
        for entry in listed {
            let array = Self::array_entry(entry, offset)?;
            let size = array
                .count
                .checked_mul(element_size(&array.kind))
                .ok_or_else(|| {
                    DashboardError::Header(format!("array {} is too long", array.name))
                })?;
            if bytes.len().saturating_sub(offset) < size {
                return Err(truncated(&format!("array {}", array.name), size, offset));
            }
            offset = padded(offset + size);
            arrays.push(array);
        }
        if offset < bytes.len() {
            return Err(DashboardError::TrailingBytes(bytes.len() - offset));
        }
        Ok(Self { header, arrays })
    }

    fn array_entry(entry: &Value, offset: usize) -> Result<DecodedArray, DashboardError> {
        let bad = || DashboardError::Header(format!("bad array entry {entry}"));
        let name = entry.get("name").and_then(Value::as_str).ok_or_else(bad)?;
        let kind = entry.get("type").and_then(Value::as_str).ok_or_else(bad)?;
        if !matches!(kind, "f32" | "u32" | "u8") {
            return Err(bad());
        }
        let count = entry.get("count").and_then(Value::as_u64).ok_or_else(bad)?;
        Ok(DecodedArray {
            name: name.into(),
            kind: kind.into(),
            count: usize::try_from(count).map_err(|_| bad())?,
            offset,
        })
    }

    /// The header's `type`.
    pub fn kind(&self) -> &str {
        self.header
            .get("type")
            .and_then(Value::as_str)
            .unwrap_or("")
    }

    /// The array called `name`.
    pub fn array(&self, name: &str) -> Option<&DecodedArray> {
        self.arrays.iter().find(|a| a.name == name)
    }

    /// An `f32` array's values.
    pub fn f32s(&self, bytes: &[u8], name: &str) -> Option<Vec<f32>> {
        let a = self.array(name).filter(|a| a.kind == "f32")?;
        let data = bytes.get(a.offset..a.offset + 4 * a.count)?;
        Some(
            data.as_chunks::<4>()
                .0
                .iter()
                .map(|c| f32::from_le_bytes(*c))
                .collect(),
        )
    }

    /// A `u32` array's values.
    pub fn u32s(&self, bytes: &[u8], name: &str) -> Option<Vec<u32>> {
        let a = self.array(name).filter(|a| a.kind == "u32")?;
        let data = bytes.get(a.offset..a.offset + 4 * a.count)?;
        Some(
            data.as_chunks::<4>()
                .0
                .iter()
                .map(|c| u32::from_le_bytes(*c))
                .collect(),
        )
    }
}

fn element_size(kind: &str) -> usize {
    if kind == "u8" {
        1
    } else {
        4
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Vec<u8> {
        Frame::new("cloud")
            .field("stream", "spheres")
            .array("positions", ArrayData::F32(vec![1.0, -2.5, 3.0]))
            .array("flags", ArrayData::U8(vec![1, 2, 3, 4, 5]))
            .array("indices", ArrayData::U32(vec![7, 8]))
            .encode()
    }

    #[test]
    fn arrays_start_on_four_byte_boundaries_and_decode_back() {
        let bytes = sample();
        assert_eq!(bytes.len() % 4, 0);
        let frame = DecodedFrame::decode(&bytes).unwrap();
        assert_eq!(frame.kind(), "cloud");
        assert_eq!(frame.header["stream"], "spheres");
        assert!(frame.arrays.iter().all(|a| a.offset % 4 == 0));
        assert_eq!(
            frame.f32s(&bytes, "positions").unwrap(),
            vec![1.0, -2.5, 3.0]
        );
        assert_eq!(frame.u32s(&bytes, "indices").unwrap(), vec![7, 8]);
        let flags = frame.array("flags").unwrap();
        assert_eq!(&bytes[flags.offset..flags.offset + 5], &[1, 2, 3, 4, 5]);
        // The header length is exact and padded with spaces.
        let h = u32::from_le_bytes(bytes[..4].try_into().unwrap()) as usize;
        assert!(bytes[4 + h..(4 + h).next_multiple_of(4)]
            .iter()
            .all(|&b| b == b' '));
        assert_eq!(
            DecodedFrame::decode(&Frame::new("nodes").encode())
                .unwrap()
                .arrays,
            vec![]
        );
    }

    #[test]
    fn truncated_padded_or_lying_frames_are_refused() {
        let bytes = sample();
        for len in 0..bytes.len() {
            assert!(DecodedFrame::decode(&bytes[..len]).is_err(), "{len}");
        }
        let mut longer = bytes.clone();
        longer.extend_from_slice(&[0; 4]);
        assert_eq!(
            DecodedFrame::decode(&longer),
            Err(DashboardError::TrailingBytes(4))
        );
        let mut lying = Frame::new("x").encode();
        let text =
            r#"{"type":"x","arrays":[{"name":"a","type":"f32","count":18446744073709551615}]}"#;
        lying.clear();
        lying.extend_from_slice(&(text.len() as u32).to_le_bytes());
        lying.extend_from_slice(text.as_bytes());
        assert!(DecodedFrame::decode(&lying).is_err());
    }
}
