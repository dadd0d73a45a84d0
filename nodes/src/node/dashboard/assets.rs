//! The page's files, embedded in the binary at build time (the dashboard needs
//! nothing on disk and fetches nothing from the internet).

use include_dir::{include_dir, Dir};

static ASSETS: Dir<'_> = include_dir!("$CARGO_MANIFEST_DIR/src/node/dashboard/assets");

/// The MIME type and bytes of the file at `path` (relative, `/`-separated).
pub fn get(path: &str) -> Option<(&'static str, &'static [u8])> {
    if path.split('/').any(|part| part == ".." || part.is_empty()) {
        return None;
    }
    let file = ASSETS.get_file(path)?;
    Some((mime(path), file.contents()))
}

fn mime(path: &str) -> &'static str {
    match path.rsplit_once('.').map(|(_, ext)| ext) {
        Some("html") => "text/html; charset=utf-8",
        Some("js" | "mjs") => "text/javascript; charset=utf-8",
        Some("css") => "text/css; charset=utf-8",
        Some("svg") => "image/svg+xml",
        Some("png") => "image/png",
        Some("json") => "application/json",
        _ => "application/octet-stream",
    }
}

/// Every embedded file's path.
#[cfg(test)]
fn paths() -> Vec<String> {
    fn walk(dir: &Dir<'_>, out: &mut Vec<String>) {
        for file in dir.files() {
            out.push(file.path().to_string_lossy().into_owned());
        }
        for sub in dir.dirs() {
            walk(sub, out);
        }
    }
    let mut out = Vec::new();
    walk(&ASSETS, &mut out);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_page_is_embedded_and_paths_cannot_escape() {
        assert!(get("index.html")
            .is_some_and(|(mime, b)| mime.starts_with("text/html") && !b.is_empty()));
        for path in paths() {
            assert!(get(&path).is_some(), "{path}");
        }
        for bad in ["../Cargo.toml", "a//b", "", "/etc/passwd", "nope.js"] {
            assert!(get(bad).is_none(), "{bad}");
        }
    }
}
