//! When a recording's chunk and file end. A chunk is closed when it holds
//! `chunk_bytes` or is `max_age_ns` old, so that a recorder killed without
//! warning (SIGKILL, power loss) loses at most its last chunk: every closed
//! chunk is complete and readable. With `--split-size`, a file is finished and
//! the next one started before a message would take it past the size.

use super::error::RecordError;
use std::path::{Path, PathBuf};

/// When the chunk being written is closed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ChunkPolicy {
    /// Uncompressed bytes of messages in a chunk at most (one message may be
    /// larger: it then fills its own chunk).
    pub chunk_bytes: u64,
    /// Age of a chunk's first message at most.
    pub max_age_ns: u64,
}

impl ChunkPolicy {
    /// Whether the open chunk (`bytes` of messages, first one written
    /// `age_ns` ago) ends now.
    pub fn should_close(&self, bytes: u64, age_ns: u64) -> bool {
        bytes > 0 && (bytes >= self.chunk_bytes || age_ns >= self.max_age_ns)
    }
}

/// Whether and where a recording continues in a new file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SplitPolicy {
    max_bytes: Option<u64>,
}

/// `--split-size` bounds, MB: below a megabyte every cloud would start a
/// file; above a terabyte the option is surely a typo.
const SPLIT_MB: std::ops::RangeInclusive<f64> = 1.0..=1_000_000.0;

impl SplitPolicy {
    /// One file, however large.
    pub fn never() -> Self {
        Self { max_bytes: None }
    }

    /// `--split-size MB`.
    pub fn from_mb(mb: f64) -> Result<Self, RecordError> {
        if !mb.is_finite() || !SPLIT_MB.contains(&mb) {
            return Err(RecordError::Option {
                option: "--split-size",
                reason: format!("{mb} MB is not between 1 MB and 1000000 MB (1 TB)"),
            });
        }
        Ok(Self {
            max_bytes: Some((mb * 1e6) as u64),
        })
    }

    pub fn splits(&self) -> bool {
        self.max_bytes.is_some()
    }

    /// Whether a message of `next_bytes` goes to a new file, the current one
    /// holding `file_bytes` in `messages` messages (a file holds at least one).
    pub fn should_split(&self, file_bytes: u64, messages: u64, next_bytes: u64) -> bool {
        self.max_bytes
            .is_some_and(|max| messages > 0 && file_bytes.saturating_add(next_bytes) > max)
    }
}

/// The path of file `index` of a recording to `base`: `base` itself when the
/// recording does not split, else `<stem>-<index:03>.<ext>` (`run.mcap` →
/// `run-000.mcap`, `run-001.mcap`...).
pub fn split_path(base: &Path, split: bool, index: u32) -> PathBuf {
    if !split {
        return base.to_path_buf();
    }
    let stem = base
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let ext = base
        .extension()
        .map(|e| format!(".{}", e.to_string_lossy()))
        .unwrap_or_default();
    base.with_file_name(format!("{stem}-{index:03}{ext}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chunks_close_on_size_or_age_never_empty() {
        let p = ChunkPolicy {
            chunk_bytes: 1000,
            max_age_ns: 1_000_000_000,
        };
        assert!(!p.should_close(0, u64::MAX));
        assert!(!p.should_close(999, 999_999_999));
        assert!(p.should_close(1000, 0));
        assert!(p.should_close(1, 1_000_000_000));
    }

    #[test]
    fn files_split_before_the_size_is_passed() {
        let p = SplitPolicy::from_mb(1.0).unwrap();
        assert!(p.splits());
        assert!(!p.should_split(900_000, 3, 100_000));
        assert!(p.should_split(900_000, 3, 100_001));
        // A message larger than the whole size still lands in a file.
        assert!(!p.should_split(100, 0, 5_000_000));
        assert!(!SplitPolicy::never().should_split(u64::MAX, 9, u64::MAX));
    }

    #[test]
    fn absurd_split_sizes_are_refused() {
        for mb in [0.0, 0.5, -3.0, f64::NAN, f64::INFINITY, 2e6] {
            let e = SplitPolicy::from_mb(mb).unwrap_err().to_string();
            assert!(e.contains("--split-size"), "{e}");
        }
    }

    #[test]
    fn split_files_are_numbered_beside_the_base() {
        let base = Path::new("/data/run.mcap");
        assert_eq!(split_path(base, false, 4), base);
        assert_eq!(split_path(base, true, 0), Path::new("/data/run-000.mcap"));
        assert_eq!(split_path(Path::new("run"), true, 12), Path::new("run-012"));
    }
}
