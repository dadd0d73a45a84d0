//! Reading an MCAP file from start to end, streaming (one chunk in memory at
//! a time), and surviving its end: a file that stops early (a recorder killed
//! mid-chunk) yields every record before the cut, and every message of every
//! complete chunk (chunk contents are checked whole before any of their
//! messages is handed out), then says where it was cut. Lengths read from the
//! file are checked against what is left of it before anything is allocated.

use anyhow::{bail, Context, Result};
use mcap::records::Record;
use mcap::sans_io::linear_reader::{LinearReadEvent, LinearReader, LinearReaderOptions};
use std::fs::File;
use std::io::Read;
use std::path::Path;

/// The largest record (and decompressed chunk) accepted: far above what
/// shroud writes (chunks of a few MB, clouds of tens of MB).
const RECORD_LIMIT: usize = 1 << 30;
/// Bytes read from the file at once at most.
const READ_STEP: u64 = 1 << 24;

/// How the file ended.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Ending {
    /// Footer and closing magic: the file was finished.
    Complete,
    /// The file stops before its end, `at_byte` bytes in: what was read
    /// before is good.
    Truncated { at_byte: u64, reason: String },
}

/// Reads `path`, handing each record to `visit` in file order; `visit`
/// returns false to stop early (the ending is then `Complete`). An empty file,
/// a file that is not MCAP, and a corrupt record are errors.
pub fn read_records(
    path: &Path,
    mut visit: impl FnMut(Record<'_>) -> Result<bool>,
) -> Result<Ending> {
    let mut file = File::open(path).with_context(|| format!("cannot open {}", path.display()))?;
    let size = file
        .metadata()
        .with_context(|| format!("cannot read {}", path.display()))?
        .len();
    if size == 0 {
        bail!("{} is empty (not an MCAP file)", path.display());
    }
    check_magic(&mut file, path)?;
    let mut file = File::open(path).with_context(|| format!("cannot open {}", path.display()))?;
    let mut reader = LinearReader::new_with_options(
        LinearReaderOptions::default()
            .with_prevalidate_chunk_crcs(true)
            .with_record_length_limit(RECORD_LIMIT),
    );
    let mut consumed: u64 = 0;
    while let Some(event) = reader.next_event() {
        let event = match event {
            Ok(event) => event,
            Err(mcap::McapError::UnexpectedEof) => {
                return Ok(truncated(
                    consumed,
                    "the file ends inside a record: it was not finished",
                ))
            }
            Err(e) => bail!("{} is corrupt after byte {consumed}: {e}", path.display()),
        };
        match event {
            LinearReadEvent::ReadRequest(need) => {
                // Never more than the file still holds (a corrupt length must
                // not size an allocation), nor more than 16 MB at once.
                let left = size.saturating_sub(consumed);
                let want = (need as u64).min(left).min(READ_STEP) as usize;
                let n = match want {
                    0 => 0,
                    _ => read_some(&mut file, reader.insert(want), path)?,
                };
                consumed += n as u64;
                reader.notify_read(n);
            }
            LinearReadEvent::Record { opcode, data } => {
                let record = mcap::parse_record(opcode, data)
                    .with_context(|| format!("{} has a corrupt record", path.display()))?;
                if !visit(record)? {
                    return Ok(Ending::Complete);
                }
            }
        }
    }
    Ok(Ending::Complete)
}

fn truncated(at_byte: u64, reason: &str) -> Ending {
    Ending::Truncated {
        at_byte,
        reason: reason.to_owned(),
    }
}

/// Refuses a file that does not start with the MCAP magic, with a clear
/// message rather than the reader's.
fn check_magic(file: &mut File, path: &Path) -> Result<()> {
    let mut start = [0u8; 8];
    let n = read_some(file, &mut start, path)?;
    if n < mcap::MAGIC.len() || start[..mcap::MAGIC.len()] != *mcap::MAGIC {
        bail!(
            "{} is not an MCAP file (it does not start with the MCAP magic bytes)",
            path.display()
        );
    }
    Ok(())
}

fn read_some(file: &mut File, buf: &mut [u8], path: &Path) -> Result<usize> {
    let mut filled = 0;
    while filled < buf.len() {
        match file.read(&mut buf[filled..]) {
            Ok(0) => break,
            Ok(n) => filled += n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e).with_context(|| format!("cannot read {}", path.display())),
        }
    }
    Ok(filled)
}
