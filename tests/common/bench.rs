//! The benchmark harness, `shroud-bench`: its own package (bench/). The
//! tests run the one beside the `shroud` binary under test (the one whose
//! nodes its graph benchmarks start). `cargo test --workspace` builds it
//! there (bench/tests needs it, with the workspace's features); a test run
//! alone builds it there once if it is missing. A `shroud-bench` left from an
//! older build is used as it is: run the workspace's tests, or
//! `cargo build -p shroud-bench`, after changing the harness.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

/// A command running the `shroud-bench` beside `shroud`.
pub fn shroud_bench() -> Command {
    static BUILT: OnceLock<PathBuf> = OnceLock::new();
    Command::new(BUILT.get_or_init(beside_shroud_or_build))
}

/// The `shroud-bench` beside `shroud`, built only when it is not there: a
/// build of that package alone resolves other features than the
/// workspace's and would compile much of the dependency tree again.
fn beside_shroud_or_build() -> PathBuf {
    let shroud = Path::new(env!("CARGO_BIN_EXE_shroud"));
    let bench = shroud.with_file_name(format!("shroud-bench{}", std::env::consts::EXE_SUFFIX));
    if bench.is_file() {
        bench
    } else {
        build()
    }
}

/// Builds `shroud-bench` with the profile of the `shroud` under test (its
/// directory: `debug` is `cargo test`'s test profile) and returns its path.
fn build() -> PathBuf {
    let shroud = Path::new(env!("CARGO_BIN_EXE_shroud"));
    let dir = shroud
        .parent()
        .expect("the shroud binary is in a directory");
    let profile = match dir.file_name().and_then(|name| name.to_str()) {
        Some("debug") => "test",
        Some(name) => name,
        None => panic!("no profile directory above {}", shroud.display()),
    };
    let target = dir
        .parent()
        .expect("a profile directory is in a target directory");
    let target = target.to_str().expect("a UTF-8 target directory");
    let args = [
        "build",
        "-p",
        "shroud-bench",
        "--profile",
        profile,
        "--target-dir",
        target,
    ];
    let out = Command::new(env!("CARGO"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(args)
        .output()
        .expect("cargo runs");
    let bench = dir.join(format!("shroud-bench{}", std::env::consts::EXE_SUFFIX));
    assert!(
        out.status.success() && bench.is_file(),
        "no shroud-bench at {} after `cargo {}`; build it so:\n{}",
        bench.display(),
        args.join(" "),
        String::from_utf8_lossy(&out.stderr)
    );
    bench
}
