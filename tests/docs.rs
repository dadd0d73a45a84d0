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

/// `path` with `.` and `..` folded away, without touching the file system.
fn normalise(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for component in path.components() {
        match component {
            std::path::Component::CurDir => {}
            std::path::Component::ParentDir => {
                out.pop();
            }
            other => out.push(other),
        }
    }
    out
}

/// A link's target without its `<>` and title; `None` for an empty link and
/// for a URL (`https:`, `mailto:`, `//host`), which leave the repository.
fn link_target(link: &str) -> Option<&str> {
    let link = link.split_whitespace().next().unwrap_or("");
    let link = link.trim_start_matches('<').trim_end_matches('>');
    let scheme = link
        .split_once(':')
        .is_some_and(|(s, _)| !s.is_empty() && s.chars().all(|c| c.is_ascii_alphanumeric()));
    (!link.is_empty() && !scheme && !link.starts_with("//")).then_some(link)
}

/// The chapters `docs/SUMMARY.md` lists, relative to docs/ (draft chapters,
/// `[title]()`, have no file and are left out).
fn summary_entries(docs: &Path) -> Vec<String> {
    let summary = std::fs::read_to_string(docs.join("SUMMARY.md")).expect("docs/SUMMARY.md");
    links(&summary)
        .iter()
        .filter_map(|l| link_target(l))
        .map(|l| l.split('#').next().unwrap().to_string())
        .collect()
}

/// The book's page for a chapter: `x.md` becomes `x.html`, a `README.md`
/// its folder's `index.html` (mdBook's index preprocessor).
fn page_of(chapter: &str) -> String {
    match chapter.strip_suffix("README.md") {
        Some(folder) if folder.is_empty() || folder.ends_with('/') => format!("{folder}index.html"),
        _ => format!("{}.html", chapter.trim_end_matches(".md")),
    }
}

/// docs/ is an mdBook book (docs/book.toml): every Markdown file in it is a
/// chapter docs/SUMMARY.md lists (mdBook leaves an unlisted file out of the
/// book), every listed chapter exists, and no chapter links out of docs/ (the
/// built book has no page there; write such a path as code instead).
#[test]
fn every_file_of_docs_is_a_chapter_of_the_book() {
    let docs = Path::new(ROOT).join("docs");
    let mut files = Vec::new();
    markdown_files(&docs, &mut files);
    let relative = |f: &Path| {
        f.strip_prefix(&docs)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/")
    };
    let listed = summary_entries(&docs);
    let mut problems = Vec::new();
    for file in &files {
        let chapter = relative(file);
        if chapter != "SUMMARY.md" && !listed.contains(&chapter) {
            problems.push(format!(
                "docs/{chapter} is not in docs/SUMMARY.md (the book would leave it out)"
            ));
        }
        let text = std::fs::read_to_string(file).unwrap();
        for link in links(&text) {
            let Some(target) = link_target(&link) else {
                continue;
            };
            let path = target.split('#').next().unwrap();
            if path.is_empty() {
                continue;
            }
            let resolved = normalise(&file.parent().unwrap().join(path));
            if path.starts_with('/') || !resolved.starts_with(&docs) {
                problems.push(format!(
                    "docs/{chapter}: ({target}) leaves docs/, so the built book has no such \
                     page; name the file as code (`launch/README.md`) instead"
                ));
            }
        }
    }
    let mut seen = BTreeSet::new();
    for chapter in &listed {
        if !seen.insert(chapter) {
            problems.push(format!("docs/SUMMARY.md lists {chapter} twice"));
        }
        if !chapter.ends_with(".md") || !docs.join(chapter).is_file() {
            problems.push(format!(
                "docs/SUMMARY.md lists {chapter}, which is not a Markdown file in docs/"
            ));
        }
    }
    assert!(
        listed.len() >= 10,
        "docs/SUMMARY.md lists {} chapters",
        listed.len()
    );
    assert!(problems.is_empty(), "the book:\n{}", problems.join("\n"));
}

/// The values of the attribute `name` (`href`, `src`) in an HTML text, with
/// `&amp;` and `%XX` decoded.
fn attribute_values(html: &str, name: &str) -> Vec<String> {
    let needle = format!("{name}=\"");
    let mut out = Vec::new();
    let mut from = 0;
    while let Some(at) = html[from..].find(&needle) {
        let start = from + at + needle.len();
        from = start;
        let before = html[..start - needle.len()].chars().next_back();
        if !before.is_some_and(char::is_whitespace) {
            continue;
        }
        if let Some(end) = html[start..].find('"') {
            out.push(percent_decode(
                &html[start..start + end].replace("&amp;", "&"),
            ));
        }
    }
    out
}

fn percent_decode(text: &str) -> String {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let hex = bytes
            .get(i + 1..i + 3)
            .and_then(|h| std::str::from_utf8(h).ok());
        match (bytes[i], hex.and_then(|h| u8::from_str_radix(h, 16).ok())) {
            (b'%', Some(byte)) => {
                out.push(byte);
                i += 3;
            }
            (byte, _) => {
                out.push(byte);
                i += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

fn html_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            html_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "html") {
            out.push(path);
        }
    }
}

/// Every relative `href` and `src` of the built book's pages that names no
/// file of the book, or an `#anchor` no element of its page has.
fn dead_links_in_book(book: &Path) -> Vec<String> {
    let mut pages = Vec::new();
    html_files(book, &mut pages);
    let mut ids = std::collections::HashMap::<PathBuf, BTreeSet<String>>::new();
    let mut dead = BTreeSet::new();
    for page in &pages {
        let html = std::fs::read_to_string(page).unwrap();
        let shown = page
            .strip_prefix(book)
            .unwrap_or(page)
            .display()
            .to_string();
        // 404.html carries `<base href="/">` (mdBook's `site-url`): its links
        // are from the book's root, wherever it is served.
        let base = match html.split_once("<base href=\"") {
            Some((_, rest)) if rest.starts_with('/') => {
                let site = &rest[..rest.find('"').unwrap_or(0)];
                book.join(site.trim_start_matches('/'))
            }
            _ => page.parent().unwrap().to_path_buf(),
        };
        let hrefs = attribute_values(&html, "href");
        for link in hrefs.into_iter().chain(attribute_values(&html, "src")) {
            let Some(target) = link_target(&link) else {
                continue;
            };
            let (path, fragment) = target.split_once('#').unwrap_or((target, ""));
            let path = path.split('?').next().unwrap();
            let mut file = if path.is_empty() {
                page.clone()
            } else if let Some(from_root) = path.strip_prefix('/') {
                book.join(from_root)
            } else {
                normalise(&base.join(path))
            };
            if file.is_dir() {
                file = file.join("index.html");
            }
            if !file.starts_with(book) || !file.is_file() {
                dead.insert(format!("{shown}: {link} (no such file in the book)"));
                continue;
            }
            if fragment.is_empty() || file.extension().is_none_or(|e| e != "html") {
                continue;
            }
            let anchors = ids.entry(file.clone()).or_insert_with(|| {
                let html = std::fs::read_to_string(&file).unwrap();
                let mut set: BTreeSet<String> = attribute_values(&html, "id").into_iter().collect();
                set.extend(attribute_values(&html, "name"));
                set
            });
            if !anchors.contains(fragment) {
                dead.insert(format!("{shown}: {link} (no such anchor)"));
            }
        }
    }
    dead.into_iter().collect()
}

/// The built book (`mdbook build docs`, into target/book; `SHROUD_BOOK_DIR`
/// names it): a page for every chapter, and every link between its pages,
/// anchors included, resolves. Skipped without SHROUD_BOOK_DIR, except under
/// `CI=true`, where .ci/run builds the book first.
#[test]
fn the_built_books_links_resolve() {
    let Some(dir) = std::env::var_os("SHROUD_BOOK_DIR") else {
        let ci = std::env::var("CI").is_ok_and(|v| v == "true");
        assert!(
            !ci,
            "CI=true but SHROUD_BOOK_DIR is not set: build the book with `mdbook build docs` \
             and export SHROUD_BOOK_DIR=target/book (as .ci/run does) so its links are checked"
        );
        eprintln!(
            "SKIP the built book's links: SHROUD_BOOK_DIR is not set \
             (`mdbook build docs && SHROUD_BOOK_DIR=target/book cargo test --test docs`)"
        );
        return;
    };
    let book = normalise(&Path::new(ROOT).join(dir));
    assert!(
        book.join("index.html").is_file(),
        "SHROUD_BOOK_DIR={} holds no index.html: run `mdbook build docs` first",
        book.display()
    );
    let docs = Path::new(ROOT).join("docs");
    let missing: Vec<String> = summary_entries(&docs)
        .iter()
        .map(|chapter| page_of(chapter))
        .filter(|page| !book.join(page).is_file())
        .collect();
    assert!(
        missing.is_empty(),
        "the book in {} has no page for {missing:?}: is it older than docs/SUMMARY.md?",
        book.display()
    );
    let dead = dead_links_in_book(&book);
    assert!(
        dead.is_empty(),
        "dead links in the built book:\n{}",
        dead.join("\n")
    );
}

#[test]
fn the_book_checker_finds_dead_links_and_anchors() {
    let book = tempfile::tempdir().unwrap();
    std::fs::create_dir(book.path().join("css")).unwrap();
    std::fs::write(book.path().join("css/a.css"), "").unwrap();
    std::fs::write(
        book.path().join("index.html"),
        "<link href=\"css/a.css\"><h1 id=\"top\">x</h1><a href=\"#top\">ok</a> \
         <a href=\"using.html#b\">ok</a> <a href=\"gone.html\">dead</a> \
         <a href=\"using.html#nope\">dead</a> <img src=\"images/x.png\"> \
         <a href=\"https://example.com/gone.html\">external</a>",
    )
    .unwrap();
    std::fs::write(
        book.path().join("using.html"),
        "<h2 id=\"b\">b</h2><a href=\"../README.html\">dead</a> <a data-href=\"x\" href=\"index.html#top\">ok</a>",
    )
    .unwrap();
    std::fs::create_dir(book.path().join("sub")).unwrap();
    std::fs::write(
        book.path().join("sub/404.html"),
        "<base href=\"/\"><link href=\"css/a.css\"><a href=\"using.html#b\">ok</a>",
    )
    .unwrap();
    let dead = dead_links_in_book(book.path());
    assert_eq!(
        dead,
        vec![
            "index.html: gone.html (no such file in the book)",
            "index.html: images/x.png (no such file in the book)",
            "index.html: using.html#nope (no such anchor)",
            "using.html: ../README.html (no such file in the book)",
        ],
    );
    assert_eq!(page_of("README.md"), "index.html");
    assert_eq!(page_of("specs/README.md"), "specs/index.html");
    assert_eq!(page_of("node-graph.md"), "node-graph.html");
}
