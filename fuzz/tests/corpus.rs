//! Replays every committed corpus input through its target on stable Rust (no
//! fuzzer): a decoder change that breaks a target's properties on an input
//! the fuzzer once found fails here. Also checks that the registry, the
//! fuzzer binaries and the corpus folders agree.

use shroud_fuzz::TARGETS;
use shroud_graph::metrics::CountingAllocator;
use std::collections::BTreeSet;
use std::fs;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};

/// Counts heap bytes so that replays check the targets' allocation bound too.
#[global_allocator]
static ALLOCATOR: CountingAllocator = CountingAllocator;

fn fuzz_dir() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn corpus_dir(name: &str) -> PathBuf {
    fuzz_dir().join("corpus").join(name)
}

fn registered() -> BTreeSet<String> {
    TARGETS.iter().map(|t| t.name.to_string()).collect()
}

#[test]
fn every_target_has_a_fuzzer_binary() {
    let manifest: toml::Table = fs::read_to_string(fuzz_dir().join("Cargo.toml"))
        .expect("fuzz/Cargo.toml")
        .parse()
        .expect("fuzz/Cargo.toml is TOML");
    let bins: BTreeSet<String> = manifest["bin"]
        .as_array()
        .expect("a bin list")
        .iter()
        .map(|b| b["name"].as_str().expect("a bin name").to_string())
        .collect();
    assert_eq!(
        bins,
        registered(),
        "fuzz/Cargo.toml's bins and src/targets/mod.rs's list"
    );
    assert_eq!(TARGETS.len(), bins.len(), "a target registered twice");
    for name in &bins {
        let binary = fuzz_dir().join("fuzz_targets").join(format!("{name}.rs"));
        let text = fs::read_to_string(&binary).unwrap_or_default();
        assert!(
            text.contains("shroud_fuzz::fuzz_binary!();"),
            "{} must call shroud_fuzz::fuzz_binary!()",
            binary.display()
        );
    }
}

#[test]
fn every_target_has_a_corpus() {
    let folders: BTreeSet<String> = fs::read_dir(fuzz_dir().join("corpus"))
        .expect("fuzz/corpus")
        .map(|e| {
            e.expect("a corpus entry")
                .file_name()
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    assert_eq!(
        folders,
        registered(),
        "fuzz/corpus's folders and the targets"
    );
    for name in registered() {
        let files = fs::read_dir(corpus_dir(&name))
            .expect("a corpus folder")
            .count();
        assert!(files > 0, "fuzz/corpus/{name} is empty");
    }
}

#[test]
fn corpus_inputs_keep_their_properties() {
    let mut failures = Vec::new();
    for target in TARGETS {
        let mut paths: Vec<PathBuf> = fs::read_dir(corpus_dir(target.name))
            .map(|d| d.map(|e| e.expect("a corpus entry").path()).collect())
            .unwrap_or_default();
        paths.sort();
        for path in paths {
            let data = fs::read(&path).expect("a corpus file");
            if catch_unwind(AssertUnwindSafe(|| shroud_fuzz::fuzz(target.name, &data))).is_err() {
                failures.push(path.display().to_string());
            }
        }
    }
    assert!(
        failures.is_empty(),
        "inputs that fail their target:\n{}",
        failures.join("\n")
    );
}

/// Writes every target's seeds to `fuzz/corpus/<name>/seed-<n>` (run by hand
/// after a format change: `cargo test -p shroud-fuzz --test corpus -- --ignored`).
#[test]
#[ignore = "rewrites the committed seeds"]
fn write_seeds() {
    for target in TARGETS {
        let dir = corpus_dir(target.name);
        fs::create_dir_all(&dir).expect("a corpus folder");
        for (i, seed) in (target.seeds)().iter().enumerate() {
            fs::write(dir.join(format!("seed-{i:02}")), seed).expect("a seed file");
        }
    }
}
