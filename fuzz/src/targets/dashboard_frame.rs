//! The dashboard's binary frames (`DecodedFrame::decode`), read as a browser
//! reads them. A decoded frame rebuilt from its header and arrays encodes to
//! a frame that decodes the same.

use crate::check::{named, same};
use serde_json::Value;
use shroud_viewers::dashboard::{ArrayData, DecodedFrame, Frame};

pub fn run(data: &[u8]) {
    match DecodedFrame::decode(data) {
        Ok(frame) => {
            let rebuilt = rebuild(&frame, data).encode();
            let again = DecodedFrame::decode(&rebuilt).expect("a rebuilt frame decodes");
            let listed = |f: &DecodedFrame| {
                f.arrays
                    .iter()
                    .map(|a| (a.name.clone(), a.kind.clone(), a.count))
                    .collect::<Vec<_>>()
            };
            same(
                &listed(&frame),
                &listed(&again),
                "arrays after a round trip",
            );
            let values = |f: &DecodedFrame, bytes: &[u8]| {
                f.arrays
                    .iter()
                    .map(|a| bytes[a.offset..a.offset + size(a)].to_vec())
                    .collect::<Vec<_>>()
            };
            same(
                &values(&frame, data),
                &values(&again, &rebuilt),
                "array bytes after a round trip",
            );
        }
        Err(e) => named(&e),
    }
}

fn size(array: &shroud_viewers::dashboard::DecodedArray) -> usize {
    if array.kind == "u8" {
        array.count
    } else {
        4 * array.count
    }
}

/// The frame's header fields (but its array list) and arrays, as a [`Frame`].
fn rebuild(frame: &DecodedFrame, bytes: &[u8]) -> Frame {
    let mut out = Frame::new(frame.kind());
    for (key, value) in frame
        .header
        .iter()
        .filter(|(k, _)| *k != "arrays" && *k != "type")
    {
        out = out.field(key, value.clone());
    }
    for array in &frame.arrays {
        let raw = &bytes[array.offset..array.offset + size(array)];
        let words = || raw.chunks_exact(4).map(|c| [c[0], c[1], c[2], c[3]]);
        let data = match array.kind.as_str() {
            "f32" => ArrayData::F32(words().map(f32::from_le_bytes).collect()),
            "u32" => ArrayData::U32(words().map(u32::from_le_bytes).collect()),
            _ => ArrayData::U8(raw.to_vec()),
        };
        out = out.array(&array.name, data);
    }
    out
}

pub fn seeds() -> Vec<Vec<u8>> {
    let frame = Frame::new("cloud")
        .field("topic", "demo/cloud/lidar")
        .field("count", Value::from(3))
        .array("points", ArrayData::F32(vec![0.0, 1.0, 2.0, 3.0, 4.0, 5.0]))
        .array("index", ArrayData::U32(vec![7, 8]))
        .array("flags", ArrayData::U8(vec![1, 2, 3]));
    vec![frame.encode(), Frame::new("hello").encode()]
}
