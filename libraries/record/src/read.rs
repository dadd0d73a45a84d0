//! Reading an MCAP recording from start to end, streaming (one chunk in
//! memory at a time), and surviving its end: a recording that stops early (a
//! recorder killed mid-chunk) yields every record before the cut and every
//! message of every complete chunk (a chunk's contents are checked whole, CRC
//! included, before any of its messages is handed out), then says where it
//! was cut. Lengths read from the file are checked against what is left of
//! it before anything is allocated. The bytes come from any reader of a known
//! size (a file in `shroud-nodes`, a slice in the fuzz target).

use super::chunk;
use super::fields::{check_fields, is_read};
use mcap::records::op;
use mcap::records::Record;
use mcap::sans_io::linear_reader::{LinearReadEvent, LinearReader, LinearReaderOptions};
use std::io::Read;
use thiserror::Error;

/// The largest record (and decompressed chunk) accepted: far above what
/// shroud writes (chunks of a few MB, clouds of tens of MB)...
const RECORD_LIMIT: usize = 1 << 30;
/// ...and at most this many bytes per byte of the file beyond
/// [`RECORD_FLOOR`]: a chunk header may claim any uncompressed size, and the
/// reader allocates what it claims (zstd rarely passes 20:1 on shroud's data).
const RECORD_PER_FILE_BYTE: usize = 1024;
const RECORD_FLOOR: usize = 64 << 20;
/// Bytes read at once at most.
const READ_STEP: u64 = 1 << 24;

/// How a recording ended.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Ending {
    /// Footer and closing magic: the file was finished (or the visitor
    /// stopped early).
    Complete,
    /// The bytes stop before the file's end, `at_byte` bytes in: what was
    /// read before is good.
    Truncated { at_byte: u64, reason: String },
}

/// Why a recording cannot be read; each reads after the file's name.
#[derive(Debug, Error)]
pub enum ReadError {
    #[error("is empty (not an MCAP file)")]
    Empty,
    #[error("is not an MCAP file (it does not start with the MCAP magic bytes)")]
    NotMcap,
    #[error("is corrupt in its first {at_byte} bytes: {reason}")]
    Corrupt { at_byte: u64, reason: String },
    #[error("cannot be read: {0}")]
    Io(#[from] std::io::Error),
}

/// Reads the `size` bytes of `source`, handing each record that shroud's
/// readers use (header, schemas, channels, messages, metadata, chunk indexes;
/// the others are skipped) to `visit` in file order; `visit` returns false to stop early (the ending is then
/// `Complete`). An empty source, one that is not MCAP and a corrupt record
/// are errors; a source that stops early is [`Ending::Truncated`].
pub fn read_records(
    mut source: impl Read,
    size: u64,
    mut visit: impl FnMut(Record<'_>) -> bool,
) -> Result<Ending, ReadError> {
    if size == 0 {
        return Err(ReadError::Empty);
    }
    let limit = record_limit(size);
    // Chunks come whole, and shroud opens them (`chunk.rs`): a chunk's
    // messages are handed out only once all of it checked out.
    let mut reader = LinearReader::new_with_options(
        LinearReaderOptions::default()
            .with_emit_chunks(true)
            .with_record_length_limit(limit),
    );
    let mut consumed: u64 = 0;
    let corrupt = |at_byte, reason: String| ReadError::Corrupt { at_byte, reason };
    while let Some(event) = reader.next_event() {
        let event = match event {
            Ok(event) => event,
            Err(mcap::McapError::BadMagic) => return Err(ReadError::NotMcap),
            Err(mcap::McapError::UnexpectedEof) if consumed < mcap::MAGIC.len() as u64 => {
                return Err(ReadError::NotMcap)
            }
            Err(mcap::McapError::UnexpectedEof) => {
                return Ok(truncated(
                    consumed,
                    "the file ends inside a record: it was not finished",
                ))
            }
            Err(e) => return Err(corrupt(consumed, e.to_string())),
        };
        match event {
            LinearReadEvent::ReadRequest(need) => {
                // Never more than the source still holds (a corrupt length
                // must not size an allocation), nor more than 16 MB at once.
                let left = size.saturating_sub(consumed);
                let want = (need as u64).min(left).min(READ_STEP) as usize;
                let n = match want {
                    0 => 0,
                    _ => read_some(&mut source, reader.insert(want))?,
                };
                consumed += n as u64;
                reader.notify_read(n);
            }
            LinearReadEvent::Record { opcode, data } => {
                let take = |opcode: u8, data: &[u8]| hand_out(opcode, data, &mut visit);
                let go_on = match opcode {
                    op::CHUNK => chunk::for_each_record(data, limit, take),
                    _ => hand_out(opcode, data, &mut visit),
                };
                match go_on {
                    Ok(true) => {}
                    Ok(false) => return Ok(Ending::Complete),
                    Err(reason) => return Err(corrupt(consumed, reason)),
                }
            }
        }
    }
    Ok(Ending::Complete)
}

/// The largest record accepted in a file of `size` bytes.
fn record_limit(size: u64) -> usize {
    let scaled = usize::try_from(size)
        .unwrap_or(usize::MAX)
        .saturating_mul(RECORD_PER_FILE_BYTE);
    scaled.clamp(RECORD_FLOOR, RECORD_LIMIT)
}

/// Checks, parses and visits one record (skipped if shroud's readers do not
/// use its kind); whether to go on, or why the record is corrupt.
fn hand_out(
    opcode: u8,
    data: &[u8],
    visit: &mut impl FnMut(Record<'_>) -> bool,
) -> Result<bool, String> {
    if !is_read(opcode) {
        return Ok(true);
    }
    check_fields(opcode, data)
        .map_err(|e| format!("a corrupt record (opcode {opcode:#04x}): {e}"))?;
    let record = mcap::parse_record(opcode, data).map_err(|e| format!("a corrupt record: {e}"))?;
    Ok(visit(record))
}

fn truncated(at_byte: u64, reason: &str) -> Ending {
    Ending::Truncated {
        at_byte,
        reason: reason.to_owned(),
    }
}

/// Fills `buf` unless the source ends first; the bytes read.
fn read_some(source: &mut impl Read, buf: &mut [u8]) -> std::io::Result<usize> {
    let mut filled = 0;
    while filled < buf.len() {
        match source.read(&mut buf[filled..]) {
            Ok(0) => break,
            Ok(n) => filled += n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
    }
    Ok(filled)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A finished recording of `messages` messages on one channel.
    fn recording(messages: u64, compression: Option<mcap::Compression>) -> Vec<u8> {
        let mut out = std::io::Cursor::new(Vec::new());
        let mut w = mcap::WriteOptions::new()
            .compression(compression)
            .chunk_size(Some(256))
            .create(&mut out)
            .unwrap();
        let schema = w.add_schema("s", "shroud-msgpack", b"{}").unwrap();
        let channel = w
            .add_channel(schema, "shroud/t/cloud/a", "msgpack", &Default::default())
            .unwrap();
        for i in 0..messages {
            let header = mcap::records::MessageHeader {
                channel_id: channel,
                sequence: i as u32,
                log_time: i,
                publish_time: i,
            };
            w.write_to_known_channel(&header, &[i as u8; 100]).unwrap();
        }
        w.finish().unwrap();
        drop(w);
        out.into_inner()
    }

    fn count(bytes: &[u8]) -> Result<(u64, Ending), ReadError> {
        let mut messages = 0;
        let ending = read_records(bytes, bytes.len() as u64, |r| {
            messages += u64::from(matches!(r, Record::Message { .. }));
            true
        })?;
        Ok((messages, ending))
    }

    #[test]
    fn a_finished_recording_is_read_whole() {
        for compression in [None, Some(mcap::Compression::Zstd)] {
            let (n, ending) = count(&recording(40, compression)).unwrap();
            assert_eq!((n, ending), (40, Ending::Complete));
        }
    }

    #[test]
    fn a_cut_recording_gives_the_messages_of_its_complete_chunks() {
        let whole = recording(40, Some(mcap::Compression::Zstd));
        let mut seen = Vec::new();
        for cut in (9..whole.len()).step_by(37) {
            let (n, ending) = count(&whole[..cut]).unwrap();
            assert!(matches!(ending, Ending::Truncated { .. }), "cut at {cut}");
            seen.push(n);
        }
        assert!(seen.windows(2).all(|w| w[0] <= w[1]), "{seen:?}");
        assert!(*seen.last().unwrap() > 30, "{seen:?}");
    }

    proptest::proptest! {
        /// Any cut and any changed bytes give records and an ending or a
        /// named error, never a panic; a cut never yields more messages than
        /// the whole.
        #[test]
        fn cut_or_changed_recordings_never_panic(
            cut in 0usize..4000,
            flips in proptest::collection::vec((0usize..4000, 1u8..=255), 0..6),
            zstd in proptest::bool::ANY,
        ) {
            let compression = zstd.then_some(mcap::Compression::Zstd);
            let mut bytes = recording(30, compression);
            let whole = count(&bytes).unwrap().0;
            let cut = cut.min(bytes.len());
            if let Ok((n, _)) = count(&bytes[..cut]) {
                proptest::prop_assert!(n <= whole);
            }
            let len = bytes.len();
            for (at, x) in flips {
                bytes[at % len] ^= x;
            }
            if let Err(e) = count(&bytes) {
                proptest::prop_assert!(!e.to_string().trim().is_empty());
            }
        }
    }

    #[test]
    fn empty_foreign_and_corrupt_bytes_are_named_errors() {
        assert!(matches!(count(b""), Err(ReadError::Empty)));
        assert!(matches!(count(b"ply\nformat"), Err(ReadError::NotMcap)));
        assert!(matches!(count(b"\x89MC"), Err(ReadError::NotMcap)));
        let mut bytes = recording(10, None);
        // A chunk's byte changed: its CRC no longer matches.
        let at = bytes.len() / 3;
        bytes[at] ^= 0xff;
        let e = count(&bytes).unwrap_err();
        assert!(e.to_string().contains("corrupt"), "{e}");
    }
}
