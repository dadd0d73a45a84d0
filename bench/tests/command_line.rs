//! The `shroud-bench` binary's command line. Being an integration test, it
//! also makes `cargo test --workspace` build the binary (with the workspace's
//! features), which the end-to-end tests in `tests/` then run.

use std::process::Command;

fn bench() -> Command {
    Command::new(env!("CARGO_BIN_EXE_shroud-bench"))
}

#[test]
fn the_help_lists_every_suite() {
    let out = bench().arg("--help").output().expect("shroud-bench runs");
    assert!(out.status.success());
    let help = String::from_utf8_lossy(&out.stdout);
    for suite in [
        "surrogate",
        "latency",
        "devices",
        "can",
        "consumers",
        "soak",
        "guard-soundness",
        "guard-separation",
        "ros2-cdr",
        "peers",
    ] {
        assert!(help.contains(suite), "{suite} missing from:\n{help}");
    }
}

#[test]
fn an_unknown_suite_is_a_named_error() {
    let out = bench()
        .arg("no-such-suite")
        .output()
        .expect("shroud-bench runs");
    assert!(!out.status.success());
    let error = String::from_utf8_lossy(&out.stderr);
    assert!(error.contains("no-such-suite"), "{error}");
}
