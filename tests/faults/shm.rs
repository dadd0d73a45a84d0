//! zenoh's shared-memory segments (`/dev/shm/<id>.zenoh`) that processes have
//! mapped or open, read from `/proc/<pid>/maps` and `/proc/<pid>/fd`: what a
//! graph created, to check that none is left once it is gone. Segments of
//! other processes on the machine are not ours to judge, so the test compares
//! only these.

use shroud_nodes::transport::is_zenoh_segment;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// The zenoh segments `pids` map or hold open now.
pub fn segments_of(pids: &[i32]) -> BTreeSet<PathBuf> {
    let mut found = BTreeSet::new();
    for pid in pids {
        let maps = std::fs::read_to_string(format!("/proc/{pid}/maps")).unwrap_or_default();
        found.extend(
            maps.lines()
                .filter_map(|line| line.split_whitespace().nth(5))
                .map(PathBuf::from)
                .filter(|p| is_zenoh_segment(p)),
        );
        let fds = std::fs::read_dir(format!("/proc/{pid}/fd"))
            .into_iter()
            .flatten();
        found.extend(
            fds.filter_map(Result::ok)
                .filter_map(|fd| std::fs::read_link(fd.path()).ok())
                .filter(|p| is_zenoh_segment(p)),
        );
    }
    found
}

/// Those of `segments` that still exist, with their sizes.
pub fn left(segments: &BTreeSet<PathBuf>) -> Vec<(PathBuf, u64)> {
    segments
        .iter()
        .filter_map(|p| Some((p.clone(), Path::new(p).metadata().ok()?.len())))
        .collect()
}
