//! candump log lines (`candump -L` / `-l` format):
//! `(1700000000.123456) can0 123#DEADBEEF`, extended ids as 8 hex digits
//! (`12345678#...`), remote frames as `123#R` or `123#R4`. Parsing and writing.

use super::frame::{CanFrame, MAX_EXTENDED_ID, MAX_STANDARD_ID};
use crate::{DecoderStats, IngestError};
use std::fmt::Write;

/// One log line: when, on which interface, which frame.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CandumpRecord {
    /// Nanoseconds since the Unix epoch (the log keeps microseconds).
    pub stamp_ns: u64,
    pub interface: String,
    pub frame: CanFrame,
}

/// Parses one line (`line_no` is for the error message). Blank lines and lines
/// starting with `#` or `;` give `Ok(None)`.
pub fn parse_candump_line(
    line: &str,
    line_no: usize,
) -> Result<Option<CandumpRecord>, IngestError> {
    let bad = |reason: &str| IngestError::BadCandump {
        line: line_no,
        reason: reason.to_owned(),
    };
    let text = line.trim();
    if text.is_empty() || text.starts_with('#') || text.starts_with(';') {
        return Ok(None);
    }
    let mut fields = text.split_ascii_whitespace();
    let (Some(stamp), Some(interface), Some(frame), None) =
        (fields.next(), fields.next(), fields.next(), fields.next())
    else {
        return Err(bad("expected `(seconds.micros) interface id#data`"));
    };
    let stamp_ns = stamp
        .strip_prefix('(')
        .and_then(|s| s.strip_suffix(')'))
        .and_then(parse_stamp)
        .ok_or_else(|| bad(&format!("bad timestamp {stamp:?}")))?;
    let frame = parse_frame(frame).map_err(|reason| bad(&reason))?;
    Ok(Some(CandumpRecord {
        stamp_ns,
        interface: interface.to_owned(),
        frame,
    }))
}

/// `seconds.fraction` (up to 9 fraction digits) to nanoseconds.
fn parse_stamp(s: &str) -> Option<u64> {
    let (secs, frac) = s.split_once('.').unwrap_or((s, ""));
    let digits = |t: &str| !t.is_empty() && t.bytes().all(|b| b.is_ascii_digit());
    if !digits(secs) || !(frac.is_empty() || digits(frac) && frac.len() <= 9) {
        return None;
    }
    let nanos: u64 = format!("{frac:0<9}").parse().ok()?;
    secs.parse::<u64>()
        .ok()?
        .checked_mul(1_000_000_000)?
        .checked_add(nanos)
}

fn parse_frame(s: &str) -> Result<CanFrame, String> {
    let (id, data) = s.split_once('#').ok_or("no `#` between id and data")?;
    if data.starts_with('#') {
        return Err("CAN FD frames are not supported".into());
    }
    let extended = match id.len() {
        3 => false,
        8 => true,
        n => return Err(format!("id {id:?} has {n} digits, not 3 or 8")),
    };
    if !id.bytes().all(|b| b.is_ascii_hexdigit()) {
        return Err(format!("id {id:?} is not hexadecimal"));
    }
    let id = u32::from_str_radix(id, 16).map_err(|e| e.to_string())?;
    let max = if extended {
        MAX_EXTENDED_ID
    } else {
        MAX_STANDARD_ID
    };
    if id > max {
        return Err(format!("id {id:#x} exceeds {max:#x}"));
    }
    if let Some(len) = data.strip_prefix('R').or_else(|| data.strip_prefix('r')) {
        let len = match len.as_bytes() {
            [] => 0,
            [d @ b'0'..=b'8'] => d - b'0',
            _ => return Err(format!("bad remote frame length {len:?}")),
        };
        return CanFrame::remote(id, extended, len).map_err(|e| e.to_string());
    }
    let hex: Vec<u8> = data.bytes().filter(|&b| b != b'.').collect();
    if !hex.len().is_multiple_of(2) || hex.len() > 16 || !hex.iter().all(u8::is_ascii_hexdigit) {
        return Err(format!("data {data:?} is not up to 8 hex bytes"));
    }
    let bytes: Vec<u8> = hex
        .chunks_exact(2)
        .map(|p| {
            u8::from_str_radix(std::str::from_utf8(p).expect("hex is ASCII"), 16).expect("hex")
        })
        .collect();
    CanFrame::new(id, extended, &bytes).map_err(|e| e.to_string())
}

/// The log line of `record` (no newline), in `candump -L` format.
pub fn format_candump_line(record: &CandumpRecord) -> String {
    let mut s = format!(
        "({}.{:06}) {} ",
        record.stamp_ns / 1_000_000_000,
        record.stamp_ns % 1_000_000_000 / 1000,
        record.interface
    );
    let f = &record.frame;
    let _ = if f.extended {
        write!(s, "{:08X}#", f.id)
    } else {
        write!(s, "{:03X}#", f.id)
    };
    if f.remote {
        s.push('R');
        if f.len > 0 {
            let _ = write!(s, "{}", f.len);
        }
    }
    for b in f.payload() {
        let _ = write!(s, "{b:02X}");
    }
    s
}

/// Line-by-line parser that numbers lines and counts what it accepts and rejects.
#[derive(Debug, Default)]
pub struct CandumpParser {
    line_no: usize,
    stats: DecoderStats,
}

impl CandumpParser {
    pub fn stats(&self) -> &DecoderStats {
        &self.stats
    }

    /// Parses the next line of the log.
    pub fn push_line(&mut self, line: &str) -> Option<Result<CandumpRecord, IngestError>> {
        self.line_no += 1;
        self.stats.input += 1;
        match parse_candump_line(line, self.line_no) {
            Ok(Some(r)) => {
                self.stats.frames += 1;
                Some(Ok(r))
            }
            Ok(None) => None,
            Err(e) => {
                self.stats.skipped_bytes += line.len() as u64;
                Some(Err(self.stats.count(e)))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn record(line: &str) -> CandumpRecord {
        parse_candump_line(line, 1).unwrap().unwrap()
    }

    #[test]
    fn reads_standard_extended_and_remote_frames() {
        let r = record("(1700000000.123456) can0 123#DEADBEEF");
        assert_eq!(r.stamp_ns, 1_700_000_000_123_456_000);
        assert_eq!(r.interface, "can0");
        assert_eq!(
            r.frame,
            CanFrame::new(0x123, false, &[0xDE, 0xAD, 0xBE, 0xEF]).unwrap()
        );
        let r = record("  (1.5) vcan1 12345678#0102.03  ");
        assert_eq!(r.stamp_ns, 1_500_000_000);
        assert_eq!(
            r.frame,
            CanFrame::new(0x1234_5678, true, &[1, 2, 3]).unwrap()
        );
        assert_eq!(record("(0.000001) can0 7FF#").frame.len, 0);
        assert_eq!(
            record("(0.000001) can0 010#R").frame,
            CanFrame::remote(0x10, false, 0).unwrap()
        );
        assert_eq!(
            record("(0.000001) can0 010#R4").frame,
            CanFrame::remote(0x10, false, 4).unwrap()
        );
        assert_eq!(parse_candump_line("", 1), Ok(None));
        assert_eq!(parse_candump_line("# comment", 1), Ok(None));
    }

    #[test]
    fn writes_what_it_reads() {
        for line in [
            "(1700000000.123456) can0 123#DEADBEEF",
            "(1700000000.000001) can1 1FFFFFFF#0102030405060708",
            "(5.000000) vcan0 010#R4",
            "(5.000000) vcan0 010#R",
            "(5.000000) vcan0 7FF#",
        ] {
            assert_eq!(format_candump_line(&record(line)), line);
        }
    }

    #[test]
    fn bad_lines_name_their_line_and_problem() {
        let mut parser = CandumpParser::default();
        let lines = [
            "(1.0) can0 123#AA",
            "1.0 can0 123#AA",
            "(1.x) can0 123#AA",
            "(1.0) can0",
            "(1.0) can0 123#AA extra",
            "(1.0) can0 12#AA",
            "(1.0) can0 800#AA",
            "(1.0) can0 20000000#AA",
            "(1.0) can0 12G#AA",
            "(1.0) can0 123#AAB",
            "(1.0) can0 123#001122334455667788",
            "(1.0) can0 123##1AA",
            "(1.0) can0 123AA",
            "(1.0) can0 123#R9",
            "(1.0) can0 123#ZZ",
            "(99999999999999999999.0) can0 123#AA",
            "(1.0) can0 123#AA",
        ];
        let results: Vec<_> = lines.iter().filter_map(|l| parser.push_line(l)).collect();
        assert!(results[0].is_ok() && results[16].is_ok());
        for (i, r) in results.iter().enumerate().take(16).skip(1) {
            match r {
                Err(IngestError::BadCandump { line, .. }) => assert_eq!(*line, i + 1),
                other => panic!("line {}: {other:?}", i + 1),
            }
        }
        assert_eq!(parser.stats().frames, 2);
        assert_eq!(parser.stats().total_errors(), 15);
    }
}
