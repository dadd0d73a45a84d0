//! An MCAP file read from start to end with `shroud-record`'s tolerant reader
//! ([`shroud_record::read_records`]: streaming, one chunk in memory at
//! a time, a truncated file read up to its cut); errors name the file.

use anyhow::{Context, Result};
use mcap::records::Record;
use shroud_record::read_records as read_bytes;
pub use shroud_record::Ending;
use std::fs::File;
use std::io::BufReader;
use std::path::Path;

/// Reads `path`, handing each record to `visit` in file order; `visit`
/// returns false to stop early (the ending is then `Complete`), or an error
/// that ends the reading and is returned.
pub fn read_records(
    path: &Path,
    mut visit: impl FnMut(Record<'_>) -> Result<bool>,
) -> Result<Ending> {
    let file = File::open(path).with_context(|| format!("cannot open {}", path.display()))?;
    let size = file
        .metadata()
        .with_context(|| format!("cannot read {}", path.display()))?
        .len();
    let mut failed = None;
    let ending = read_bytes(BufReader::new(file), size, |record| match visit(record) {
        Ok(go_on) => go_on,
        Err(e) => {
            failed = Some(e);
            false
        }
    })
    .map_err(|e| anyhow::anyhow!("{} {e}", path.display()))?;
    match failed {
        Some(e) => Err(e),
        None => Ok(ending),
    }
}
