//! Python virtual environments for the tests that run a real Python client:
//! one venv per package set under the target directory, created once and
//! shared by the tests of a run (they run in parallel: one creates it while
//! the others wait). Packages come from PyPI, the one registry CI reaches.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The interpreter of the venv `name`, with `packages` (pinned `pip`
/// requirements) installed; panics with pip's error when PyPI cannot be
/// reached, so a missing package is a failure, never a skip.
pub fn python_with(name: &str, packages: &[&str]) -> PathBuf {
    static CREATING: std::sync::Mutex<()> = std::sync::Mutex::new(());
    let _one_at_a_time = CREATING.lock().unwrap_or_else(|e| e.into_inner());
    let venv = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let py = venv.join("bin/python3");
    // The marker holds the package list: a changed pin makes a new venv.
    let ready = venv.join(".ready");
    let wanted = packages.join("\n");
    if std::fs::read_to_string(&ready).ok().as_deref() != Some(wanted.as_str()) {
        let _ = std::fs::remove_dir_all(&venv);
        let status = Command::new("python3")
            .args(["-m", "venv"])
            .arg(&venv)
            .status()
            .expect("python3 runs");
        assert!(status.success(), "python3 -m venv failed");
        let out = Command::new(&py)
            .args([
                "-m",
                "pip",
                "install",
                "--quiet",
                "--disable-pip-version-check",
            ])
            .args(packages)
            .output()
            .expect("pip runs");
        assert!(
            out.status.success(),
            "pip install {packages:?} failed (needs the PyPI registry): {}",
            String::from_utf8_lossy(&out.stderr)
        );
        std::fs::write(&ready, &wanted).unwrap();
    }
    py
}
