//! Removing zenoh's shared-memory segments at exit, which zenoh 1.10 leaves
//! behind on its own.
//!
//! zenoh names its POSIX segments `/dev/shm/<id>.zenoh` and removes one only
//! when no process holds a lock on it (every process that maps one holds a
//! shared `flock`); it looks for such orphans when a process creates its first
//! segment and when it exits. At exit, though, the exiting process still holds
//! the locks of its own process-wide segments (the chunk metadata segment, a
//! static never dropped), so its own orphan search cannot remove them: every
//! process that used shared memory leaves at least that segment (1.25 MiB)
//! until another zenoh process on the machine starts or exits (observed with
//! strace: the exclusive `flock` of the exit-time search fails with EAGAIN on
//! the process's own segment). A node whose launcher was killed, or the last
//! process of a graph, would leave it for good.
//!
//! [`release_shm_segments`] runs once a process is done with zenoh: it drops
//! this process's locks on zenoh segments and runs zenoh's orphan search, which
//! then removes every segment no other live process holds (this process's own,
//! and those of processes that already died, such as a launcher killed with
//! SIGKILL). A segment another process still maps keeps its lock and stays;
//! that process removes it when it exits. Unlinking a name does not unmap it:
//! this process's remaining threads may still touch their mappings.

use std::os::unix::ffi::OsStrExt;
use std::path::Path;

/// Where zenoh's POSIX segments live, and how their names end.
const SHM_DIR: &str = "/dev/shm";
const ZENOH_SUFFIX: &str = ".zenoh";

/// Releases this process's locks on zenoh segments and removes every segment
/// no live process holds. Call it only after the process's zenoh sessions are
/// closed: a segment removed while a session still publishes from it could not
/// be opened by a subscriber that had not mapped it yet.
pub fn release_shm_segments() {
    for fd in zenoh_segment_fds() {
        // SAFETY: flock(2) on a descriptor this process has open; unlocking
        // changes nothing but the advisory lock.
        unsafe {
            libc::flock(fd, libc::LOCK_UN);
        }
    }
    zenoh::shm::cleanup_orphaned_shm_segments();
}

/// This process's open descriptors on zenoh segments (`/proc/self/fd`).
fn zenoh_segment_fds() -> Vec<libc::c_int> {
    let Ok(entries) = std::fs::read_dir("/proc/self/fd") else {
        return Vec::new();
    };
    entries
        .filter_map(Result::ok)
        .filter_map(|entry| {
            let fd = entry.file_name().to_str()?.parse().ok()?;
            let target = std::fs::read_link(entry.path()).ok()?;
            is_zenoh_segment(&target).then_some(fd)
        })
        .collect()
}

/// `/dev/shm/<digits>.zenoh`, as zenoh names a segment.
pub fn is_zenoh_segment(path: &Path) -> bool {
    path.parent() == Some(Path::new(SHM_DIR))
        && path.file_name().is_some_and(|name| {
            let name = name.as_bytes();
            name.strip_suffix(ZENOH_SUFFIX.as_bytes())
                .is_some_and(|id| !id.is_empty() && id.iter().all(u8::is_ascii_digit))
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_zenoh_segments_only() {
        assert!(is_zenoh_segment(Path::new("/dev/shm/4752.zenoh")));
        assert!(is_zenoh_segment(Path::new("/dev/shm/3284630235.zenoh")));
        for other in [
            "/dev/shm/.zenoh",
            "/dev/shm/x1.zenoh",
            "/dev/shm/12.zenoh.bak",
            "/tmp/12.zenoh",
            "/dev/shm/sub/12.zenoh",
        ] {
            assert!(!is_zenoh_segment(Path::new(other)), "{other}");
        }
    }
}
