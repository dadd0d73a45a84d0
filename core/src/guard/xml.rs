//! A minimal XML reader for URDF: elements with attributes, nested; text,
//! comments, processing instructions, DOCTYPE and CDATA are skipped. Enough for
//! robot descriptions, not a general XML parser (no namespaces, no DTD
//! entities beyond the five predefined ones).

/// An element with its attributes (in order) and child elements.
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct Element {
    pub name: String,
    pub attributes: Vec<(String, String)>,
    pub children: Vec<Element>,
}

impl Element {
    pub fn attribute(&self, name: &str) -> Option<&str> {
        self.attributes
            .iter()
            .find(|(k, _)| k == name)
            .map(|(_, v)| v.as_str())
    }

    pub fn children_named<'a>(&'a self, name: &'a str) -> impl Iterator<Item = &'a Element> {
        self.children.iter().filter(move |c| c.name == name)
    }

    pub fn child(&self, name: &str) -> Option<&Element> {
        self.children.iter().find(|c| c.name == name)
    }
}

/// Deepest nesting accepted (URDF needs about five levels).
const MAX_DEPTH: usize = 64;

/// The document's root element.
pub(crate) fn parse(text: &str) -> Result<Element, String> {
    let mut stack: Vec<Element> = Vec::new();
    let mut root: Option<Element> = None;
    let mut rest = text;
    while let Some(start) = rest.find('<') {
        let offset = text.len() - rest.len() + start;
        rest = &rest[start..];
        if let Some(skip) = [("<?", "?>"), ("<!--", "-->"), ("<![CDATA[", "]]>")]
            .iter()
            .find(|(open, _)| rest.starts_with(open))
        {
            let end = rest
                .find(skip.1)
                .ok_or_else(|| format!("unterminated '{}' at byte {offset}", skip.0))?;
            rest = &rest[end + skip.1.len()..];
            continue;
        }
        if rest.starts_with("<!") {
            let end = rest
                .find('>')
                .ok_or_else(|| format!("unterminated declaration at byte {offset}"))?;
            rest = &rest[end + 1..];
            continue;
        }
        let end = tag_end(rest).ok_or_else(|| format!("unterminated tag at byte {offset}"))?;
        let tag = &rest[1..end];
        rest = &rest[end + 1..];
        if let Some(name) = tag.strip_prefix('/') {
            let name = name.trim();
            let open = stack.pop().ok_or_else(|| {
                format!("closing tag </{name}> without an open one at byte {offset}")
            })?;
            if open.name != name {
                return Err(format!(
                    "closing tag </{name}> does not match <{}> at byte {offset}",
                    open.name
                ));
            }
            close(open, &mut stack, &mut root)?;
            continue;
        }
        let (tag, self_closing) = match tag.strip_suffix('/') {
            Some(t) => (t, true),
            None => (tag, false),
        };
        let element = element_of(tag).map_err(|e| format!("{e} at byte {offset}"))?;
        if self_closing {
            close(element, &mut stack, &mut root)?;
        } else {
            if stack.len() >= MAX_DEPTH {
                return Err(format!("elements nested deeper than {MAX_DEPTH}"));
            }
            stack.push(element);
        }
    }
    if let Some(open) = stack.last() {
        return Err(format!("element <{}> is never closed", open.name));
    }
    root.ok_or_else(|| "no element found".to_string())
}

/// Index of the `>` ending the tag that starts `s`, outside quoted values.
fn tag_end(s: &str) -> Option<usize> {
    let mut quote = None;
    for (i, c) in s.char_indices().skip(1) {
        match (quote, c) {
            (None, '"' | '\'') => quote = Some(c),
            (Some(q), c) if c == q => quote = None,
            (None, '>') => return Some(i),
            _ => {}
        }
    }
    None
}

/// Attaches a finished element to its parent, or makes it the root.
fn close(
    element: Element,
    stack: &mut [Element],
    root: &mut Option<Element>,
) -> Result<(), String> {
    match stack.last_mut() {
        Some(parent) => parent.children.push(element),
        None if root.is_none() => *root = Some(element),
        None => return Err(format!("a second root element <{}>", element.name)),
    }
    Ok(())
}

/// `name a="1" b='2'` to an element without children.
fn element_of(tag: &str) -> Result<Element, String> {
    let tag = tag.trim();
    let name_end = tag.find(char::is_whitespace).unwrap_or(tag.len());
    let name = &tag[..name_end];
    if name.is_empty() {
        return Err("empty tag name".into());
    }
    let mut attributes = Vec::new();
    let mut rest = tag[name_end..].trim_start();
    while !rest.is_empty() {
        let eq = rest
            .find('=')
            .ok_or_else(|| format!("attribute without value in <{name}>"))?;
        let key = rest[..eq].trim();
        let after = rest[eq + 1..].trim_start();
        let quote = after
            .chars()
            .next()
            .filter(|c| *c == '"' || *c == '\'')
            .ok_or_else(|| format!("unquoted value of '{key}' in <{name}>"))?;
        let close = after[1..]
            .find(quote)
            .ok_or_else(|| format!("unterminated value of '{key}' in <{name}>"))?;
        attributes.push((key.to_string(), unescape(&after[1..1 + close])));
        rest = after[close + 2..].trim_start();
    }
    Ok(Element {
        name: name.to_string(),
        attributes,
        children: Vec::new(),
    })
}

fn unescape(s: &str) -> String {
    s.replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&apos;", "'")
        .replace("&amp;", "&")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_nested_elements_and_skips_the_rest() {
        let doc = r#"<?xml version="1.0"?>
            <!DOCTYPE robot>
            <!-- a comment with <tags> -->
            <robot name="r">
              text is ignored
              <link name='a &amp; b'><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
              <joint name="j" type="fixed"><parent link="a"/><child link="b" /></joint>
            </robot>"#;
        let root = parse(doc).unwrap();
        assert_eq!(root.name, "robot");
        assert_eq!(root.attribute("name"), Some("r"));
        let link = root.child("link").unwrap();
        assert_eq!(link.attribute("name"), Some("a & b"));
        let sphere = link
            .child("collision")
            .and_then(|c| c.child("geometry"))
            .and_then(|g| g.child("sphere"))
            .unwrap();
        assert_eq!(sphere.attribute("radius"), Some("0.1"));
        assert_eq!(root.children_named("joint").count(), 1);
        assert_eq!(
            root.child("joint")
                .and_then(|j| j.child("child"))
                .and_then(|c| c.attribute("link")),
            Some("b")
        );
    }

    #[test]
    fn malformed_documents_are_refused() {
        for bad in [
            "",
            "<robot>",
            "<robot></link>",
            "</robot>",
            "<robot name=x/>",
            "<robot name=\"x/>",
            "<a/><b/>",
            "<!-- never closed",
            "<robot",
            "< />",
        ] {
            assert!(parse(bad).is_err(), "{bad:?}");
        }
        let deep = "<a>".repeat(100) + &"</a>".repeat(100);
        assert!(parse(&deep).is_err());
    }
}
