//! Topic filters of `--topics`: comma-separated `<kind>/<name>` patterns over
//! shroud's topic kinds (`cloud/*`, `surrogate/spheres`, `*/fit`, `status/scan?er`),
//! where the kind is a [`TopicKind`] name or `*` and the name a glob (`*` any run
//! of characters, `?` one character).

use super::error::RecordError;
use shroud_msg::{TopicKey, TopicKind, ROOT};

/// One `<kind>/<name>` pattern.
#[derive(Debug, Clone, PartialEq, Eq)]
struct Pattern {
    /// `None` for `*`: every kind.
    kind: Option<TopicKind>,
    name: String,
}

/// A set of patterns; a topic is taken when any pattern matches it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TopicFilter {
    patterns: Vec<Pattern>,
}

/// Longest pattern accepted (a stream name is at most 64 characters).
const MAX_PATTERN: usize = 80;

impl TopicFilter {
    /// Every topic of every kind.
    pub fn all() -> Self {
        Self::parse("*/*").expect("a valid pattern")
    }

    /// Parses `--topics`: comma-separated patterns, at least one.
    pub fn parse(text: &str) -> Result<Self, RecordError> {
        let patterns = text
            .split(',')
            .map(str::trim)
            .filter(|p| !p.is_empty())
            .map(parse_pattern)
            .collect::<Result<Vec<_>, _>>()?;
        if patterns.is_empty() {
            return Err(RecordError::Filter {
                pattern: text.to_owned(),
                reason: "no pattern: give <kind>/<name> patterns such as cloud/*,surrogate/*"
                    .into(),
            });
        }
        Ok(Self { patterns })
    }

    /// The same filter without the topics of `kind` (a pattern `*/x` keeps
    /// matching the other kinds).
    pub fn without(&self, kind: TopicKind) -> Self {
        let patterns = self
            .patterns
            .iter()
            .flat_map(|p| match p.kind {
                Some(k) if k == kind => Vec::new(),
                Some(_) => vec![p.clone()],
                None => TopicKind::ALL
                    .into_iter()
                    .filter(|&k| k != kind && k != TopicKind::Alive)
                    .map(|k| Pattern {
                        kind: Some(k),
                        name: p.name.clone(),
                    })
                    .collect(),
            })
            .collect();
        Self { patterns }
    }

    pub fn matches(&self, key: &TopicKey) -> bool {
        self.patterns
            .iter()
            .any(|p| p.kind.is_none_or(|k| k == key.kind) && glob_matches(&p.name, &key.name))
    }

    /// The zenoh key expressions to subscribe to in `namespace` (one per kind
    /// named, or one for every kind); [`Self::matches`] then picks the names.
    pub fn subscriptions(&self, namespace: &str) -> Vec<String> {
        if self.patterns.iter().any(|p| p.kind.is_none()) {
            return vec![format!("{ROOT}/{namespace}/*/*")];
        }
        let mut kinds: Vec<TopicKind> = self.patterns.iter().filter_map(|p| p.kind).collect();
        kinds.sort_by_key(|k| k.as_str());
        kinds.dedup();
        kinds
            .into_iter()
            .map(|k| format!("{ROOT}/{namespace}/{k}/*"))
            .collect()
    }
}

fn parse_pattern(text: &str) -> Result<Pattern, RecordError> {
    let fail = |reason: &str| RecordError::Filter {
        pattern: text.to_owned(),
        reason: reason.to_owned(),
    };
    if text.len() > MAX_PATTERN {
        return Err(fail("longer than 80 characters"));
    }
    let Some((kind, name)) = text.split_once('/') else {
        return Err(fail(
            "must be <kind>/<name>, e.g. cloud/* or surrogate/spheres",
        ));
    };
    let kind =
        match kind {
            "*" => None,
            k => match TopicKind::parse(k) {
                Some(TopicKind::Alive) => return Err(fail(
                    "alive/... keys are liveliness tokens, not messages: they cannot be recorded",
                )),
                Some(kind) => Some(kind),
                None => {
                    return Err(fail(&format!(
                        "{k:?} is not a topic kind ({}, or *)",
                        recordable_kinds().join(", ")
                    )))
                }
            },
        };
    let name_ok = !name.is_empty()
        && name
            .bytes()
            .all(|b| b.is_ascii_alphanumeric() || matches!(b, b'-' | b'_' | b'.' | b'*' | b'?'));
    if !name_ok {
        return Err(fail(
            "the name must be letters, digits, '-', '_', '.' and the wildcards '*' and '?'",
        ));
    }
    Ok(Pattern {
        kind,
        name: name.to_owned(),
    })
}

fn recordable_kinds() -> Vec<&'static str> {
    TopicKind::ALL
        .into_iter()
        .filter(|&k| k != TopicKind::Alive)
        .map(TopicKind::as_str)
        .collect()
}

/// `*` matches any run of characters (also none), `?` exactly one. Iterative
/// with one backtrack point (the last `*`): linear in practice, never
/// exponential.
fn glob_matches(pattern: &str, name: &str) -> bool {
    let (p, n) = (pattern.as_bytes(), name.as_bytes());
    let (mut i, mut j) = (0, 0);
    let mut star: Option<(usize, usize)> = None;
    while j < n.len() {
        if i < p.len() && (p[i] == b'?' || p[i] == n[j]) {
            i += 1;
            j += 1;
        } else if i < p.len() && p[i] == b'*' {
            star = Some((i, j));
            i += 1;
        } else if let Some((si, sj)) = star {
            i = si + 1;
            j = sj + 1;
            star = Some((si, sj + 1));
        } else {
            return false;
        }
    }
    p[i..].iter().all(|&c| c == b'*')
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(kind: TopicKind, name: &str) -> TopicKey {
        TopicKey {
            namespace: "demo".into(),
            kind,
            name: name.into(),
        }
    }

    #[test]
    fn globs_match_names() {
        for (pattern, name, expected) in [
            ("*", "spheres", true),
            ("sph*", "spheres", true),
            ("*res", "spheres", true),
            ("s*e*s", "spheres", true),
            ("sph?res", "spheres", true),
            ("sph?res", "sphres", false),
            ("spheres", "spheres", true),
            ("spheres", "sphere", false),
            ("a*b", "acb-x", false),
            ("**", "", true),
        ] {
            assert_eq!(glob_matches(pattern, name), expected, "{pattern} {name}");
        }
    }

    #[test]
    fn patterns_pick_kinds_and_names() {
        let f = TopicFilter::parse("cloud/*, surrogate/sph*").unwrap();
        assert!(f.matches(&key(TopicKind::Cloud, "x")));
        assert!(f.matches(&key(TopicKind::Surrogate, "spheres")));
        assert!(!f.matches(&key(TopicKind::Surrogate, "table")));
        assert!(!f.matches(&key(TopicKind::Status, "fit")));
        assert_eq!(
            f.subscriptions("demo"),
            vec!["shroud/demo/cloud/*", "shroud/demo/surrogate/*"]
        );
        let any = TopicFilter::parse("*/fit").unwrap();
        assert!(any.matches(&key(TopicKind::Status, "fit")));
        assert!(!any.matches(&key(TopicKind::Status, "scanner")));
        assert_eq!(any.subscriptions("lab"), vec!["shroud/lab/*/*"]);
    }

    #[test]
    fn without_a_kind_keeps_the_others() {
        let f = TopicFilter::all().without(TopicKind::Status);
        assert!(!f.matches(&key(TopicKind::Status, "fit")));
        assert!(f.matches(&key(TopicKind::Cloud, "fit")));
        assert!(f.matches(&key(TopicKind::Collision, "arm")));
        let only_status = TopicFilter::parse("status/*").unwrap();
        assert!(!only_status
            .without(TopicKind::Status)
            .matches(&key(TopicKind::Status, "fit")));
    }

    #[test]
    fn bad_patterns_are_named_errors() {
        for (bad, needle) in [
            ("", "no pattern"),
            (" , ", "no pattern"),
            ("cloud", "<kind>/<name>"),
            ("clouds/*", "not a topic kind"),
            ("alive/*", "liveliness"),
            ("cloud/", "the name"),
            ("cloud/a/b", "the name"),
            ("cloud/[ab]", "the name"),
            ("cloud/a b", "the name"),
        ] {
            let e = TopicFilter::parse(bad).unwrap_err().to_string();
            assert!(e.contains(needle), "{bad:?}: {e}");
        }
        let long = format!("cloud/{}", "a".repeat(90));
        assert!(TopicFilter::parse(&long).is_err());
    }
}
