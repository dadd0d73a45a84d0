//! The one Wavefront OBJ tokenizer and parser, shared by the triangle-mesh
//! reader ([`super::parse_triangle_mesh`]) and the quad-mesh reader
//! (`crate::mesh::parse_obj`): `v` and `f` statements to vertices and polygons,
//! every other statement ignored, each defect an [`ObjDefect`] naming its line.
//!
//! The rules, the same for both readers:
//!
//! * A leading UTF-8 byte-order mark is skipped.
//! * Lines end at `\n` (a `\r` before it is whitespace); each line must be UTF-8;
//!   `#` starts a comment up to the end of the line.
//! * Tokens are separated by ASCII whitespace. A `v` or `f` line separated by
//!   any other whitespace (no-break space, vertical tab, ...) is refused; other
//!   statements (`vt`, `vn`, `g`, `o`, `s`, `usemtl`, `mtllib`, `l`, ...) are
//!   ignored whatever they hold.
//! * `v x y z [more numbers]`: every value must be a number (a `w` or an `r g b`
//!   colour may follow x, y, z and is ignored), x, y and z finite.
//! * `f a b c ...`: references `a`, `a/t`, `a//n` or `a/t/n`, 1-based or negative
//!   (counting back from the last vertex defined so far); only the vertex index
//!   before the first `/` is read, the rest of a reference is ignored. Every reference of a
//!   face is read before its number of corners is checked. Positive references
//!   may point at vertices defined later; they are checked at the end.
//! * The first defect in file order is reported; end-of-file checks (forward
//!   references) come after every line.

/// Vertex count limit: every index must fit in a `u32`.
const MAX_VERTICES: usize = u32::MAX as usize;

/// How many corners a face must have.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Corners {
    Exactly(usize),
    AtLeast(usize),
}

impl Corners {
    fn allows(self, count: usize) -> bool {
        match self {
            Corners::Exactly(n) => count == n,
            Corners::AtLeast(n) => count >= n,
        }
    }
}

/// One face: the line it is on and its number of corners.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct ObjFace {
    pub(crate) line: usize,
    pub(crate) corners: usize,
}

/// The vertices and polygons of an OBJ file, every index checked.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct ObjPolygons {
    pub(crate) vertices: Vec<[f64; 3]>,
    /// The 0-based corner indices of every face, one face after the other; each
    /// is less than `vertices.len()`.
    pub(crate) indices: Vec<u32>,
    pub(crate) faces: Vec<ObjFace>,
}

impl ObjPolygons {
    /// Each face with its line and its corner indices.
    pub(crate) fn polygons(&self) -> impl Iterator<Item = (usize, &[u32])> {
        let mut start = 0;
        self.faces.iter().map(move |face| {
            let corners = &self.indices[start..start + face.corners];
            start += face.corners;
            (face.line, corners)
        })
    }
}

/// Why bytes are not OBJ polygons. Line numbers start at 1.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum ObjDefect {
    NotUtf8 {
        line: usize,
    },
    /// A `v` or `f` line with whitespace other than ASCII's.
    NotAsciiSpace {
        line: usize,
        space: char,
    },
    VertexNotNumber {
        line: usize,
        token: String,
    },
    VertexTooFewValues {
        line: usize,
        count: usize,
    },
    VertexNotFinite {
        line: usize,
        axis: char,
        value: f64,
    },
    TooManyVertices {
        count: usize,
    },
    /// A face reference whose vertex part is not an integer.
    ReferenceNotIndex {
        line: usize,
        token: String,
    },
    ReferenceZero {
        line: usize,
        token: String,
    },
    /// A negative reference reaching before the first vertex.
    ReferenceBeforeFirst {
        line: usize,
        index: i64,
        defined: usize,
    },
    /// A positive reference beyond what a `u32` index holds.
    ReferenceTooLarge {
        line: usize,
        token: String,
        index: i64,
        defined: usize,
    },
    FaceCorners {
        line: usize,
        count: usize,
    },
    /// A positive reference past the last vertex of the file.
    ReferenceOutOfRange {
        line: usize,
        index: i64,
        vertices: usize,
    },
}

/// Parses the `v` and `f` statements of OBJ bytes; every face must have
/// `corners` corners.
pub(crate) fn parse_obj_polygons(bytes: &[u8], corners: Corners) -> Result<ObjPolygons, ObjDefect> {
    // A UTF-8 byte-order mark is not part of the first statement (it would
    // hide a first `v` and shift every vertex after it).
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    let mut out = ObjPolygons::default();
    // Positive references past the vertices defined so far: (line, 1-based index).
    let mut forward: Vec<(usize, i64)> = Vec::new();
    for (number, raw) in bytes.split(|&b| b == b'\n').enumerate() {
        let line = number + 1;
        let text = std::str::from_utf8(raw).map_err(|_| ObjDefect::NotUtf8 { line })?;
        let content = text.split('#').next().unwrap_or_default();
        let mut tokens = content.split(char::is_whitespace).filter(|t| !t.is_empty());
        let keyword = tokens.next();
        if !matches!(keyword, Some("v" | "f")) {
            continue;
        }
        if let Some(space) = content
            .chars()
            .find(|c| c.is_whitespace() && !c.is_ascii_whitespace())
        {
            return Err(ObjDefect::NotAsciiSpace { line, space });
        }
        if keyword == Some("v") {
            let xyz = vertex(tokens, line)?;
            if out.vertices.len() >= MAX_VERTICES {
                return Err(ObjDefect::TooManyVertices {
                    count: out.vertices.len() + 1,
                });
            }
            out.vertices.push(xyz);
        } else {
            let defined = out.vertices.len();
            let start = out.indices.len();
            for token in tokens {
                let index = reference(token, line, defined)?;
                if index as usize >= defined {
                    forward.push((line, i64::from(index) + 1));
                }
                out.indices.push(index);
            }
            let count = out.indices.len() - start;
            if !corners.allows(count) {
                return Err(ObjDefect::FaceCorners { line, count });
            }
            out.faces.push(ObjFace {
                line,
                corners: count,
            });
        }
    }
    let vertices = out.vertices.len();
    if let Some(&(line, index)) = forward.iter().find(|(_, i)| *i as u64 > vertices as u64) {
        return Err(ObjDefect::ReferenceOutOfRange {
            line,
            index,
            vertices,
        });
    }
    Ok(out)
}

/// The x, y, z of a `v` statement's values (all numbers, at least three, x, y
/// and z finite).
fn vertex<'a>(tokens: impl Iterator<Item = &'a str>, line: usize) -> Result<[f64; 3], ObjDefect> {
    let mut xyz = [0.0; 3];
    let mut count = 0;
    for token in tokens {
        let value = token
            .parse::<f64>()
            .map_err(|_| ObjDefect::VertexNotNumber {
                line,
                token: token.to_string(),
            })?;
        if let Some(slot) = xyz.get_mut(count) {
            *slot = value;
        }
        count += 1;
    }
    if count < 3 {
        return Err(ObjDefect::VertexTooFewValues { line, count });
    }
    if let Some(k) = xyz.iter().position(|c| !c.is_finite()) {
        return Err(ObjDefect::VertexNotFinite {
            line,
            axis: ['x', 'y', 'z'][k],
            value: xyz[k],
        });
    }
    Ok(xyz)
}

/// The 0-based vertex index of a face reference `a`, `a/t`, `a//n` or `a/t/n`.
/// Negative references count back from the last of the `defined` vertices;
/// positive ones may point past them (checked at the end of the file).
fn reference(token: &str, line: usize, defined: usize) -> Result<u32, ObjDefect> {
    let vertex = token.split('/').next().unwrap_or_default();
    let index: i64 = vertex.parse().map_err(|_| ObjDefect::ReferenceNotIndex {
        line,
        token: token.to_string(),
    })?;
    let resolved = match index {
        0 => {
            return Err(ObjDefect::ReferenceZero {
                line,
                token: token.to_string(),
            })
        }
        i if i < 0 => {
            let back = i.unsigned_abs();
            if back > defined as u64 {
                return Err(ObjDefect::ReferenceBeforeFirst {
                    line,
                    index,
                    defined,
                });
            }
            defined as u64 - back
        }
        i => i as u64 - 1,
    };
    u32::try_from(resolved).map_err(|_| ObjDefect::ReferenceTooLarge {
        line,
        token: token.to_string(),
        index,
        defined,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_byte_order_mark_hides_no_vertex() {
        let text = b"\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        let read = parse_obj_polygons(text, Corners::AtLeast(3)).unwrap();
        assert_eq!(read.vertices.len(), 3);
        assert_eq!(read.polygons().count(), 1);
    }

    #[test]
    fn polygons_references_and_defect_order() {
        let text = b"v 0 0 0\nv 1 0 0 1\nv 1 1 0\nf 1 2/1 3//1 -1\nf -3 -2 -1 # tri\n";
        let read = parse_obj_polygons(text, Corners::AtLeast(3)).unwrap();
        let faces: Vec<_> = read.polygons().collect();
        assert_eq!(faces, vec![(4, &[0, 1, 2, 2][..]), (5, &[0, 1, 2][..])]);
        assert_eq!(
            parse_obj_polygons(text, Corners::Exactly(4)).unwrap_err(),
            ObjDefect::FaceCorners { line: 5, count: 3 }
        );
        // The first defect in file order wins, forward references last.
        let two = b"f 1 2 9\nv 0 0\n\xff\n";
        assert_eq!(
            parse_obj_polygons(two, Corners::AtLeast(3)).unwrap_err(),
            ObjDefect::VertexTooFewValues { line: 2, count: 2 }
        );
        assert_eq!(
            parse_obj_polygons(b"v 0\xc2\xa00 0\n", Corners::AtLeast(3)).unwrap_err(),
            ObjDefect::NotAsciiSpace {
                line: 1,
                space: '\u{a0}'
            }
        );
        // Other statements are ignored whatever their spacing.
        assert!(parse_obj_polygons(b"g\xc2\xa0a b\n", Corners::AtLeast(3)).is_ok());
    }
}
