//! URDF's XML as a small tree of elements with attributes: roxmltree parses,
//! this keeps only what a robot description is read from.

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

/// Most XML nodes (elements, text, comments) a document may hold: a robot
/// description has hundreds; the cap bounds the memory an absurd file takes.
const MAX_NODES: u32 = 1_000_000;

/// The document's root element, parsed by roxmltree (well-formedness,
/// entities, namespaces; a DTD is allowed, as robot descriptions sometimes
/// carry one, with roxmltree's guard against entity expansion). URDF's
/// elements are in the root's namespace (usually none) and its attributes
/// in none: others (a leftover `xacro:` element or attribute) are dropped,
/// and a prefix without its `xmlns` declaration is an error, as XML has it. Text, comments and
/// processing instructions are dropped.
pub(crate) fn parse(text: &str) -> Result<Element, String> {
    let options = roxmltree::ParsingOptions {
        allow_dtd: true,
        nodes_limit: MAX_NODES,
    };
    let doc = roxmltree::Document::parse_with_options(text, options).map_err(|e| e.to_string())?;
    let root = doc.root_element();
    element_of(root, root.tag_name().namespace(), 1)
}

/// `node` and its element children in the root's namespace (none, or a
/// default `xmlns` on `<robot>`) as an [`Element`] tree.
fn element_of(
    node: roxmltree::Node<'_, '_>,
    namespace: Option<&str>,
    depth: usize,
) -> Result<Element, String> {
    if depth > MAX_DEPTH {
        return Err(format!("elements nested deeper than {MAX_DEPTH}"));
    }
    let children = node
        .children()
        .filter(|c| c.is_element() && c.tag_name().namespace() == namespace)
        .map(|c| element_of(c, namespace, depth + 1))
        .collect::<Result<_, _>>()?;
    Ok(Element {
        name: node.tag_name().name().to_string(),
        attributes: node
            .attributes()
            .filter(|a| a.namespace().is_none())
            .map(|a| (a.name().to_string(), a.value().to_string()))
            .collect(),
        children,
    })
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
        // A prefix nobody declared.
        assert!(parse("<robot><xacro:include/></robot>").is_err());
    }

    #[test]
    fn namespaced_elements_and_attributes_are_not_urdf() {
        let doc = r#"<robot xmlns:x="urn:x" x:name="other" name="r"><x:link name="no"/><link name="yes"/></robot>"#;
        let root = parse(doc).unwrap();
        assert_eq!(root.attribute("name"), Some("r"));
        assert_eq!(root.children.len(), 1);
        assert_eq!(root.child("link").unwrap().attribute("name"), Some("yes"));
        // A default namespace on the root is the document's own.
        let root = parse(r#"<robot xmlns="urn:u" name="r"><link name="a"/></robot>"#).unwrap();
        assert_eq!(root.child("link").unwrap().attribute("name"), Some("a"));
    }
}
