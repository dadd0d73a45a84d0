//! CAN frames from fuzz input: fixed 14-byte records (flags, id, time step,
//! data) so that the fuzzer mutates frames field by field, and the inverse
//! for seeds.
//!
//! | byte  | meaning                                                        |
//! |-------|----------------------------------------------------------------|
//! | 0     | bit 7 extended id, bit 6 remote, low nibble length (mod 9)     |
//! | 1..5  | id, little endian, masked to 11 or 29 bits                     |
//! | 5     | milliseconds since the previous frame                          |
//! | 6..14 | data bytes (the first `length` are used)                       |

use shroud_drivers::can::{CanFrame, MAX_EXTENDED_ID, MAX_STANDARD_ID};

/// Bytes of one record.
pub const RECORD_LEN: usize = 14;

/// A frame and the milliseconds since the previous one.
#[derive(Debug, Clone, Copy)]
pub struct Record {
    pub frame: CanFrame,
    pub step_ms: u8,
}

/// The records of `data` (a trailing partial record is ignored).
pub fn records(data: &[u8]) -> impl Iterator<Item = Record> + '_ {
    data.chunks_exact(RECORD_LEN).map(|r| {
        let extended = r[0] & 0x80 != 0;
        let len = (r[0] & 0x0F) % 9;
        let id = u32::from_le_bytes([r[1], r[2], r[3], r[4]])
            & if extended {
                MAX_EXTENDED_ID
            } else {
                MAX_STANDARD_ID
            };
        let frame = if r[0] & 0x40 != 0 {
            CanFrame::remote(id, extended, len)
        } else {
            CanFrame::new(id, extended, &r[6..6 + usize::from(len)])
        };
        Record {
            frame: frame.expect("a masked id and a length of at most 8 make a frame"),
            step_ms: r[5],
        }
    })
}

/// The record of `frame`, `step_ms` after the previous one.
pub fn record(frame: &CanFrame, step_ms: u8) -> Vec<u8> {
    let flags = (u8::from(frame.extended) << 7) | (u8::from(frame.remote) << 6) | frame.len;
    let mut out = vec![flags];
    out.extend_from_slice(&frame.id.to_le_bytes());
    out.push(step_ms);
    out.extend_from_slice(&frame.data);
    out
}
