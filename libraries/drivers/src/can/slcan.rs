//! SLCAN (Lawicel ASCII) codec: CAN frames and adapter commands as `\r`-ended
//! lines (`tIIILDD..`, `TIIIIIIIILDD..`, `rIIIL`, `RIIIIIIIIL`, `O`, `C`, `Sn`).
//! The decoder is streaming and skips (and counts) any line it cannot read.

use super::frame::{CanFrame, MAX_EXTENDED_ID, MAX_STANDARD_ID};
use crate::{DecoderStats, IngestError};

/// Longest line the decoder buffers; longer ones are garbage.
pub const MAX_LINE: usize = 64;

/// The bitrates of the `S0`..`S8` commands, in bit/s.
pub const BITRATES: [u32; 9] = [
    10_000, 20_000, 50_000, 100_000, 125_000, 250_000, 500_000, 800_000, 1_000_000,
];

/// One decoded SLCAN line.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum SlcanMessage {
    /// A received (or to be sent) CAN frame; `timestamp_ms` when the adapter
    /// appends its 0..59999 ms timer (`Z1` mode).
    Frame {
        frame: CanFrame,
        timestamp_ms: Option<u16>,
    },
    /// `O` (or `L`, listen only): open the channel.
    Open { listen_only: bool },
    /// `C`: close the channel.
    Close,
    /// `Sn`: set the bitrate, in bit/s.
    Bitrate(u32),
    /// An empty line or `z`/`Z`: the adapter's "OK".
    Ack,
    /// Any other well-formed command or reply (`V`, `N`, `F`, `Z0`, `s...`).
    Other(String),
}

/// The `Sn` digit for a bitrate, if it is a standard one.
pub fn bitrate_code(bps: u32) -> Option<u8> {
    BITRATES.iter().position(|&b| b == bps).map(|i| i as u8)
}

/// Appends the line of `frame`, `\r` included.
pub fn write_frame(frame: &CanFrame, out: &mut Vec<u8>) {
    use std::io::Write;
    let kind = match (frame.remote, frame.extended) {
        (false, false) => 't',
        (false, true) => 'T',
        (true, false) => 'r',
        (true, true) => 'R',
    };
    let len = frame.len.min(8);
    let _ = if frame.extended {
        write!(out, "{kind}{:08X}{len}", frame.id)
    } else {
        write!(out, "{kind}{:03X}{len}", frame.id)
    };
    for b in frame.payload() {
        let _ = write!(out, "{b:02X}");
    }
    out.push(b'\r');
}

/// The line of `frame`.
pub fn encode_frame(frame: &CanFrame) -> Vec<u8> {
    let mut out = Vec::with_capacity(32);
    write_frame(frame, &mut out);
    out
}

/// What a host sends to start an adapter: close, set bitrate, open
/// (`C\rSn\rO\r`). Fails on a non-standard bitrate.
pub fn open_commands(bitrate: u32) -> Result<Vec<u8>, IngestError> {
    let code = bitrate_code(bitrate).ok_or_else(|| IngestError::Malformed {
        what: "SLCAN bitrate",
        reason: format!("{bitrate} bit/s is not one of {BITRATES:?}"),
    })?;
    Ok(format!("C\rS{code}\rO\r").into_bytes())
}

/// Streaming SLCAN decoder. Lines end in `\r` (a `\n` also ends one, so
/// `\r\n` works); a BEL byte is the adapter's "error" reply.
#[derive(Debug, Default)]
pub struct SlcanDecoder {
    line: Vec<u8>,
    overflow: bool,
    stats: DecoderStats,
}

impl SlcanDecoder {
    pub fn stats(&self) -> &DecoderStats {
        &self.stats
    }

    /// Feeds bytes; returns the messages and the errors of every completed line.
    pub fn push(&mut self, bytes: &[u8]) -> Vec<Result<SlcanMessage, IngestError>> {
        self.stats.input += bytes.len() as u64;
        let mut out = Vec::new();
        for &b in bytes {
            match b {
                b'\r' | b'\n' => {
                    if self.overflow {
                        self.overflow = false;
                        self.line.clear();
                        continue;
                    }
                    if self.line.is_empty() && b == b'\n' {
                        continue;
                    }
                    let result = parse_line(&self.line);
                    match &result {
                        Ok(_) => self.stats.frames += 1,
                        Err(_) => self.stats.skipped_bytes += self.line.len() as u64 + 1,
                    }
                    out.push(result.map_err(|e| self.stats.count(e)));
                    self.line.clear();
                }
                0x07 => {
                    self.stats.skipped_bytes += self.line.len() as u64;
                    self.line.clear();
                    out.push(Err(self.stats.count(IngestError::SlcanNak)));
                }
                _ if self.overflow => self.stats.skipped_bytes += 1,
                _ if self.line.len() == MAX_LINE => {
                    self.overflow = true;
                    self.stats.skipped_bytes += self.line.len() as u64 + 1;
                    let line = String::from_utf8_lossy(&self.line).into_owned();
                    self.line.clear();
                    out.push(Err(self.stats.count(IngestError::BadSlcan {
                        line,
                        reason: "line too long",
                    })));
                }
                _ => self.line.push(b),
            }
        }
        out
    }

    /// Drops a partial line (after a reconnect), counting its bytes as skipped.
    pub fn reset(&mut self) {
        self.stats.skipped_bytes += self.line.len() as u64;
        self.line.clear();
        self.overflow = false;
    }
}

/// Parses one line without its terminator.
pub fn parse_line(line: &[u8]) -> Result<SlcanMessage, IngestError> {
    let bad = |reason| IngestError::BadSlcan {
        line: String::from_utf8_lossy(line).into_owned(),
        reason,
    };
    let Ok(text) = std::str::from_utf8(line) else {
        return Err(bad("not ASCII"));
    };
    if !text.is_ascii() || text.bytes().any(|b| b.is_ascii_control()) {
        return Err(bad("not ASCII"));
    }
    let Some(first) = text.chars().next() else {
        return Ok(SlcanMessage::Ack);
    };
    let rest = &text[1..];
    match first {
        't' | 'T' | 'r' | 'R' => parse_frame(first, rest).ok_or_else(|| bad("malformed frame")),
        'O' | 'L' if rest.is_empty() => Ok(SlcanMessage::Open {
            listen_only: first == 'L',
        }),
        'C' if rest.is_empty() => Ok(SlcanMessage::Close),
        'S' => match rest.as_bytes() {
            [d @ b'0'..=b'8'] => Ok(SlcanMessage::Bitrate(BITRATES[usize::from(d - b'0')])),
            _ => Err(bad("unknown bitrate")),
        },
        'z' | 'Z' if rest.is_empty() => Ok(SlcanMessage::Ack),
        'V' | 'v' | 'N' | 'F' | 'Z' | 's' | 'X' | 'W' | 'M' | 'm' | 'A' | 'P' => {
            Ok(SlcanMessage::Other(text.to_owned()))
        }
        _ => Err(bad("unknown command")),
    }
}

fn parse_frame(kind: char, rest: &str) -> Option<SlcanMessage> {
    if !rest.bytes().all(|b| b.is_ascii_hexdigit()) {
        return None;
    }
    let extended = kind.is_ascii_uppercase();
    let remote = matches!(kind, 'r' | 'R');
    let id_len = if extended { 8 } else { 3 };
    let id = u32::from_str_radix(rest.get(..id_len)?, 16).ok()?;
    let len = match rest.as_bytes().get(id_len)? {
        d @ b'0'..=b'8' => d - b'0',
        _ => return None,
    };
    let body = &rest[id_len + 1..];
    let data_len = if remote { 0 } else { 2 * usize::from(len) };
    let timestamp_ms = match body.len().checked_sub(data_len)? {
        0 => None,
        4 => Some(u16::from_str_radix(&body[data_len..], 16).ok()?),
        _ => return None,
    };
    let max = if extended {
        MAX_EXTENDED_ID
    } else {
        MAX_STANDARD_ID
    };
    if id > max {
        return None;
    }
    let mut data = [0u8; 8];
    for (i, byte) in data.iter_mut().take(data_len / 2).enumerate() {
        *byte = u8::from_str_radix(body.get(2 * i..2 * i + 2)?, 16).ok()?;
    }
    let frame = CanFrame {
        id,
        extended,
        remote,
        len,
        data,
    };
    Some(SlcanMessage::Frame {
        frame,
        timestamp_ms,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frames_of(messages: Vec<Result<SlcanMessage, IngestError>>) -> Vec<CanFrame> {
        messages
            .into_iter()
            .filter_map(|m| match m {
                Ok(SlcanMessage::Frame { frame, .. }) => Some(frame),
                _ => None,
            })
            .collect()
    }

    #[test]
    fn frames_round_trip_in_all_four_kinds() {
        let frames = [
            CanFrame::new(0x123, false, &[0xDE, 0xAD, 0xBE, 0xEF]).unwrap(),
            CanFrame::new(0x1234_5678, true, &[1, 2, 3, 4, 5, 6, 7, 8]).unwrap(),
            CanFrame::new(0x7FF, false, &[]).unwrap(),
            CanFrame::remote(0x010, false, 4).unwrap(),
            CanFrame::remote(0x1FFF_FFFF, true, 0).unwrap(),
        ];
        let mut bytes = Vec::new();
        for f in &frames {
            write_frame(f, &mut bytes);
        }
        assert_eq!(
            String::from_utf8(bytes.clone()).unwrap(),
            "t1234DEADBEEF\rT1234567880102030405060708\rt7FF0\rr0104\rR1FFFFFFF0\r"
        );
        for chunk in [1, 5, 100] {
            let mut decoder = SlcanDecoder::default();
            let got: Vec<_> = bytes.chunks(chunk).flat_map(|c| decoder.push(c)).collect();
            assert_eq!(frames_of(got), frames);
            assert_eq!(decoder.stats().total_errors(), 0);
        }
    }

    #[test]
    fn commands_replies_and_timestamps_are_read() {
        let mut decoder = SlcanDecoder::default();
        let got = decoder.push(b"C\rS6\rO\rL\r\rz\rV1013\r\x07t1231AA1F3C\r\n");
        let expected = vec![
            Ok(SlcanMessage::Close),
            Ok(SlcanMessage::Bitrate(500_000)),
            Ok(SlcanMessage::Open { listen_only: false }),
            Ok(SlcanMessage::Open { listen_only: true }),
            Ok(SlcanMessage::Ack),
            Ok(SlcanMessage::Ack),
            Ok(SlcanMessage::Other("V1013".into())),
            Err(IngestError::SlcanNak),
            Ok(SlcanMessage::Frame {
                frame: CanFrame::new(0x123, false, &[0xAA]).unwrap(),
                timestamp_ms: Some(0x1F3C),
            }),
        ];
        assert_eq!(got, expected);
        assert_eq!(open_commands(500_000).unwrap(), b"C\rS6\rO\r");
        assert!(open_commands(333_000).is_err());
        assert_eq!(bitrate_code(1_000_000), Some(8));
    }

    #[test]
    fn garbage_lines_are_counted_and_frames_after_them_survive() {
        let mut decoder = SlcanDecoder::default();
        let mut input = Vec::new();
        input.extend_from_slice(b"t12\rt1239AA\rx\rt8000\rT2000000000\rt1232001\rS9\rt123G00\r");
        input.extend_from_slice(&[0xFF; 100]);
        input.extend_from_slice(b"\rt12-1AA\rt1232+1AA\rt1231AA\r");
        let got = decoder.push(&input);
        let frames = frames_of(got.clone());
        assert_eq!(frames, vec![CanFrame::new(0x123, false, &[0xAA]).unwrap()]);
        let errors = got.iter().filter(|r| r.is_err()).count();
        assert_eq!(errors, 11);
        assert_eq!(decoder.stats().errors(crate::ErrorKind::BadSlcan), 11);
        assert!(decoder.stats().skipped_bytes > 100);
    }

    #[test]
    fn random_bytes_never_panic() {
        let mut x = 0x2545_F491u32;
        let mut decoder = SlcanDecoder::default();
        for _ in 0..200 {
            let bytes: Vec<u8> = (0..97)
                .map(|_| {
                    x ^= x << 13;
                    x ^= x >> 17;
                    x ^= x << 5;
                    // Mostly SLCAN's alphabet, so lines get far into the parser.
                    let alphabet = b"tTrR0123456789ABCDEFabcdef\r\x07OCS8Z";
                    alphabet[x as usize % alphabet.len()]
                })
                .collect();
            let _ = decoder.push(&bytes);
        }
    }
}
