//! The documentation's links: every relative link in the repository's
//! Markdown files names a file that exists, and every `#anchor` a heading of
//! the file it points into (GitHub's anchor rule), so the book has no dead
//! links.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

/// The Markdown files of the repository, outside build and dependency folders.
fn markdown_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let skip = ["target", "node_modules", ".git", "corpus", "artifacts"];
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if path.is_dir() {
            if !skip.contains(&name.as_str()) && !name.starts_with('.') {
                markdown_files(&path, out);
            }
        } else if name.ends_with(".md") {
            out.push(path);
        }
    }
}

/// The text outside fenced code blocks.
fn prose(text: &str) -> String {
    let mut inside = false;
    let mut out = String::new();
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            inside = !inside;
            continue;
        }
        if !inside {
            out.push_str(line);
            out.push('\n');
        }
    }
    out
}

/// GitHub's anchor of a heading: lower case, punctuation but `-` and `_`
/// dropped, spaces as `-`.
fn anchor(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || matches!(c, '-' | '_' | ' '))
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

fn anchors(text: &str) -> BTreeSet<String> {
    prose(text)
        .lines()
        .filter(|l| l.starts_with('#'))
        .map(|l| anchor(l.trim_start_matches('#')))
        .collect()
}

/// The targets of `[text](target)` links, outside code.
fn links(text: &str) -> Vec<String> {
    let prose = prose(text);
    let mut out = Vec::new();
    let mut rest = prose.as_str();
    while let Some(at) = rest.find("](") {
        rest = &rest[at + 2..];
        if let Some(end) = rest.find(')') {
            out.push(rest[..end].trim().to_string());
            rest = &rest[end..];
        }
    }
    out
}

#[test]
fn every_relative_link_and_anchor_resolves() {
    let mut files = Vec::new();
    markdown_files(Path::new(ROOT), &mut files);
    assert!(files.len() >= 10, "{} Markdown files", files.len());
    let mut dead = Vec::new();
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        for link in links(&text) {
            // `[x](<path> "title")`: the target is the first word.
            let link = link.split_whitespace().next().unwrap_or("");
            let link = link
                .trim_start_matches('<')
                .trim_end_matches('>')
                .to_string();
            let external = ["http://", "https://", "mailto:"];
            if link.is_empty() || external.iter().any(|p| link.starts_with(p)) {
                continue;
            }
            let (path, fragment) = match link.split_once('#') {
                Some((p, f)) => (p, Some(f)),
                None => (link.as_str(), None),
            };
            let target = if path.is_empty() {
                file.clone()
            } else if let Some(from_root) = path.strip_prefix('/') {
                Path::new(ROOT).join(from_root)
            } else {
                file.parent().unwrap().join(path)
            };
            let shown = file
                .strip_prefix(ROOT)
                .unwrap_or(file)
                .display()
                .to_string();
            if !target.exists() {
                dead.push(format!("{shown}: {link} (no such file)"));
                continue;
            }
            if let Some(fragment) = fragment {
                let is_markdown = target.extension().is_some_and(|e| e == "md");
                if is_markdown {
                    let headings = anchors(&std::fs::read_to_string(&target).unwrap());
                    if !headings.contains(fragment) {
                        dead.push(format!("{shown}: {link} (no such heading)"));
                    }
                }
            }
        }
    }
    assert!(dead.is_empty(), "dead links:\n{}", dead.join("\n"));
}

#[test]
fn anchors_follow_githubs_rule() {
    assert_eq!(
        anchor(" Guard soundness: brute force"),
        "guard-soundness-brute-force"
    );
    assert_eq!(
        anchor("`shroud launch` and --graph"),
        "shroud-launch-and---graph"
    );
    let text = "# A\n```\n# not a heading\n[x](y.md)\n```\n[z](w.md#a)\n[t](v.md \"title\")\n";
    assert_eq!(links(text), vec!["w.md#a", "v.md \"title\""]);
    assert!(anchors(text).contains("a") && !anchors(text).contains("not-a-heading"));
}

/// The crate graph `docs/design.md` draws, from the workspace's manifests:
/// one Mermaid edge per normal dependency between the library crates, the
/// simulator and the nodes (the binary, the fuzz targets and dev-dependencies
/// left out).
fn crate_graph() -> String {
    let output = std::process::Command::new(env!("CARGO"))
        .args([
            "metadata",
            "--no-deps",
            "--format-version",
            "1",
            "--offline",
        ])
        .current_dir(ROOT)
        .output()
        .expect("cargo metadata runs");
    assert!(output.status.success(), "cargo metadata failed");
    let metadata: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    let packages = metadata["packages"].as_array().unwrap();
    let drawn = |name: &str| name.starts_with("shroud-") && name != "shroud-fuzz";
    let mut edges = BTreeSet::new();
    for package in packages {
        let name = package["name"].as_str().unwrap();
        if !drawn(name) {
            continue;
        }
        for dependency in package["dependencies"].as_array().unwrap() {
            let target = dependency["name"].as_str().unwrap();
            if drawn(target) && dependency["kind"].is_null() {
                let id = |crate_name: &str| crate_name.replace('-', "_");
                edges.insert(format!("    {} --> {}", id(name), id(target)));
            }
        }
    }
    let mut text = String::from("```mermaid\ngraph TD\n");
    for edge in edges {
        text.push_str(&edge);
        text.push('\n');
    }
    text.push_str("```\n");
    text
}

#[test]
fn the_crate_graph_in_the_design_chapter_is_current() {
    let graph = crate_graph();
    let design = std::fs::read_to_string(Path::new(ROOT).join("docs/design.md")).unwrap();
    assert!(
        design.contains(&graph),
        "docs/design.md must embed the crate graph as it is now:\n{graph}"
    );
}
