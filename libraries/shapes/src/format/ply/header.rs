//! The PLY header: magic, format line, elements and their properties, up to
//! `end_header`. Comments and `obj_info` lines are ignored.

use crate::format::scalar::ScalarType;
use crate::format::FormatError;

/// How the body after the header is encoded.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Encoding {
    Ascii,
    BinaryLittleEndian,
    BinaryBigEndian,
}

/// A scalar, or a list of scalars preceded by its length.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PropertyKind {
    Scalar(ScalarType),
    List { count: ScalarType, item: ScalarType },
}

#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Property {
    pub name: String,
    pub kind: PropertyKind,
}

#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Element {
    pub name: String,
    pub count: usize,
    pub properties: Vec<Property>,
}

impl Element {
    /// Record size in a binary body, or `None` if a list property makes it vary.
    pub fn fixed_record_size(&self) -> Option<usize> {
        self.properties.iter().try_fold(0, |size, p| match p.kind {
            PropertyKind::Scalar(t) => Some(size + t.size()),
            PropertyKind::List { .. } => None,
        })
    }

    /// Byte offset of each property inside a binary record (meaningful up to the
    /// first list property).
    pub fn record_offsets(&self) -> Vec<usize> {
        let sizes = self.properties.iter().map(|p| match p.kind {
            PropertyKind::Scalar(t) => t.size(),
            PropertyKind::List { count, .. } => count.size(),
        });
        sizes
            .scan(0, |next, size| {
                let offset = *next;
                *next += size;
                Some(offset)
            })
            .collect()
    }

    /// Index of the scalar property called `name` (ASCII case-insensitive).
    pub fn scalar_property(&self, name: &str) -> Option<usize> {
        self.properties.iter().position(|p| {
            p.name.eq_ignore_ascii_case(name) && matches!(p.kind, PropertyKind::Scalar(_))
        })
    }
}

#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Header {
    pub encoding: Encoding,
    pub elements: Vec<Element>,
    /// Byte offset of the body (just after the `end_header` line).
    pub body_offset: usize,
    /// 1-based number of the first body line (for ASCII error messages).
    pub body_line: usize,
}

/// Whether `bytes` starts with the PLY magic line.
pub fn has_ply_magic(bytes: &[u8]) -> bool {
    bytes.starts_with(b"ply\n") || bytes.starts_with(b"ply\r\n")
}

/// Parses the header at the start of `bytes`.
pub fn parse_header(bytes: &[u8]) -> Result<Header, FormatError> {
    if !has_ply_magic(bytes) {
        return Err(FormatError::PlyMissingMagic);
    }
    let mut builder = HeaderBuilder::default();
    let mut start = 0;
    let mut line = 0;
    while start < bytes.len() {
        line += 1;
        let end = bytes[start..]
            .iter()
            .position(|&b| b == b'\n')
            .map_or(bytes.len(), |i| start + i);
        let next = (end + 1).min(bytes.len());
        if line > 1 {
            let text = std::str::from_utf8(&bytes[start..end])
                .map_err(|_| malformed(line, "the header must be ASCII text".into()))?;
            if builder.line(line, text)? {
                return builder.finish(next, line + 1);
            }
        }
        start = next;
    }
    Err(FormatError::PlyMissingEndHeader)
}

fn malformed(line: usize, reason: String) -> FormatError {
    FormatError::PlyMalformedHeader { line, reason }
}

#[derive(Default)]
struct HeaderBuilder {
    encoding: Option<Encoding>,
    elements: Vec<Element>,
}

impl HeaderBuilder {
    /// Consumes one header line; `true` at `end_header`.
    fn line(&mut self, line: usize, text: &str) -> Result<bool, FormatError> {
        let tokens: Vec<&str> = text.split_ascii_whitespace().collect();
        match tokens.first().copied() {
            None | Some("comment") | Some("obj_info") => {}
            Some("format") => self.format(line, &tokens)?,
            Some("element") => self.element(line, &tokens)?,
            Some("property") => self.property(line, &tokens)?,
            Some("end_header") => return Ok(true),
            Some(other) => return Err(malformed(line, format!("unknown keyword '{other}'"))),
        }
        Ok(false)
    }

    fn format(&mut self, line: usize, tokens: &[&str]) -> Result<(), FormatError> {
        let [_, name, _version] = tokens else {
            return Err(malformed(
                line,
                "expected 'format <encoding> <version>'".into(),
            ));
        };
        if self.encoding.is_some() {
            return Err(malformed(line, "a second 'format' line".into()));
        }
        self.encoding = Some(match *name {
            "ascii" => Encoding::Ascii,
            "binary_little_endian" => Encoding::BinaryLittleEndian,
            "binary_big_endian" => Encoding::BinaryBigEndian,
            other => {
                return Err(FormatError::PlyUnknownFormat {
                    line,
                    found: other.into(),
                })
            }
        });
        Ok(())
    }

    fn element(&mut self, line: usize, tokens: &[&str]) -> Result<(), FormatError> {
        let [_, name, count] = tokens else {
            return Err(malformed(line, "expected 'element <name> <count>'".into()));
        };
        let count = count.parse().map_err(|_| {
            malformed(
                line,
                format!("element count '{count}' is not a non-negative integer"),
            )
        })?;
        if self.elements.iter().any(|e| e.name == *name) {
            return Err(malformed(line, format!("a second element named '{name}'")));
        }
        self.elements.push(Element {
            name: (*name).into(),
            count,
            properties: Vec::new(),
        });
        Ok(())
    }

    fn property(&mut self, line: usize, tokens: &[&str]) -> Result<(), FormatError> {
        let scalar = |name: &str| {
            ScalarType::from_name(name).ok_or_else(|| FormatError::PlyUnsupportedType {
                line,
                name: name.into(),
            })
        };
        let (name, kind) = match tokens {
            [_, "list", count, item, name] => {
                let count = scalar(count)?;
                if !count.is_integer() {
                    return Err(malformed(line, format!("list length type '{}' is not an integer type", tokens[2])));
                }
                (*name, PropertyKind::List { count, item: scalar(item)? })
            }
            [_, ty, name] if *ty != "list" => (*name, PropertyKind::Scalar(scalar(ty)?)),
            _ => {
                return Err(malformed(
                    line,
                    "expected 'property <type> <name>' or 'property list <count type> <item type> <name>'".into(),
                ))
            }
        };
        let Some(element) = self.elements.last_mut() else {
            return Err(malformed(
                line,
                format!("property '{name}' comes before any element"),
            ));
        };
        if element.properties.iter().any(|p| p.name == name) {
            return Err(malformed(
                line,
                format!("a second property '{name}' in element '{}'", element.name),
            ));
        }
        element.properties.push(Property {
            name: name.into(),
            kind,
        });
        Ok(())
    }

    fn finish(self, body_offset: usize, body_line: usize) -> Result<Header, FormatError> {
        let encoding = self.encoding.ok_or(FormatError::PlyMissingFormat)?;
        Ok(Header {
            encoding,
            elements: self.elements,
            body_offset,
            body_line,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_elements_and_properties() {
        let text = "ply\r\nformat binary_big_endian 1.0\ncomment hi\nelement vertex 2\nproperty double y\n\
                    property uchar x\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\n\
                    end_header\nBODY";
        let h = parse_header(text.as_bytes()).unwrap();
        assert_eq!(h.encoding, Encoding::BinaryBigEndian);
        assert_eq!(h.elements.len(), 2);
        assert_eq!(h.elements[0].fixed_record_size(), Some(13));
        assert_eq!(h.elements[0].scalar_property("X"), Some(1));
        assert_eq!(h.elements[1].fixed_record_size(), None);
        assert_eq!(&text.as_bytes()[h.body_offset..], b"BODY");
        assert_eq!(h.body_line, 11);
    }

    #[test]
    fn names_the_broken_line() {
        let err = |t: &str| parse_header(t.as_bytes()).unwrap_err();
        assert_eq!(err("PLY\n"), FormatError::PlyMissingMagic);
        assert_eq!(
            err("ply\nformat ascii 1.0\n"),
            FormatError::PlyMissingEndHeader
        );
        assert_eq!(
            err("ply\nelement v 1\nend_header\n"),
            FormatError::PlyMissingFormat
        );
        assert_eq!(
            err("ply\nformat utf8 1.0\nend_header\n"),
            FormatError::PlyUnknownFormat {
                line: 2,
                found: "utf8".into()
            }
        );
        assert_eq!(
            err("ply\nformat ascii 1.0\nelement v 1\nproperty half x\nend_header\n"),
            FormatError::PlyUnsupportedType {
                line: 4,
                name: "half".into()
            }
        );
        assert!(matches!(
            err("ply\nformat ascii 1.0\nelement v -3\nend_header\n"),
            FormatError::PlyMalformedHeader { line: 3, .. }
        ));
        assert!(matches!(
            err("ply\nformat ascii 1.0\nproperty float x\nend_header\n"),
            FormatError::PlyMalformedHeader { line: 3, .. }
        ));
        assert!(matches!(
            err("ply\nformat ascii 1.0\nelement v 1\nproperty list float int i\nend_header\n"),
            FormatError::PlyMalformedHeader { line: 4, .. }
        ));
    }
}
