//! The golden payloads rosbags wrote (tests/golden/generate.py), shared by the tests.

#![allow(dead_code)]

use std::path::{Path, PathBuf};

fn golden_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden")
}

/// The bytes of `tests/golden/<name>.hex`.
pub fn golden(name: &str) -> Vec<u8> {
    let path = golden_dir().join(format!("{name}.hex"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    hex(text.trim())
}

/// Bytes from lowercase hex.
pub fn hex(text: &str) -> Vec<u8> {
    assert!(text.len().is_multiple_of(2), "odd hex length");
    (0..text.len())
        .step_by(2)
        .map(|i| u8::from_str_radix(&text[i..i + 2], 16).expect("hex digits"))
        .collect()
}

/// Every golden case's name, sorted.
pub fn golden_names() -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(golden_dir())
        .expect("tests/golden")
        .filter_map(|e| {
            let name = e
                .expect("an entry")
                .file_name()
                .to_string_lossy()
                .into_owned();
            name.strip_suffix(".hex").map(str::to_owned)
        })
        .collect();
    names.sort();
    names
}

/// The lines of `tests/golden/<file>`, split at the first space.
pub fn golden_pairs(file: &str) -> Vec<(String, String)> {
    let text = std::fs::read_to_string(golden_dir().join(file)).expect("a golden text file");
    text.lines()
        .map(|line| {
            let (a, b) = line.split_once(' ').expect("two columns");
            (a.to_string(), b.to_string())
        })
        .collect()
}
