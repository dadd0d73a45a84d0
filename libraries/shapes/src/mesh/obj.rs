//! Wavefront OBJ quad meshes as bytes: `v x y z` and `f a b c d` lines (with optional
//! `/vt/vn` parts and negative indices), other statements ignored. The file is
//! read by the parser shared with the triangle-mesh reader (`crate::format`),
//! whose rules apply here too; this reader requires every face to be a quad.

use std::fmt::Write as _;

use thiserror::Error;

use super::error::MeshError;
use super::quad_mesh::QuadMesh;
use crate::format::{parse_obj_polygons, Corners, ObjDefect};

/// Why bytes are not an OBJ quad mesh. Line numbers start at 1.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ObjError {
    #[error("line {line}: not valid UTF-8")]
    NotUtf8 { line: usize },
    #[error("line {line}: whitespace U+{:04X} is not an OBJ separator (use ASCII spaces or tabs)", u32::from(*space))]
    NotAsciiSpace { line: usize, space: char },
    #[error("line {line}: a vertex needs three numeric coordinates")]
    BadVertex { line: usize },
    #[error("line {line}: coordinate {axis} is {value}, must be finite")]
    NonFiniteVertex { line: usize, axis: char, value: f64 },
    #[error("line {line}: face has {corners} vertices but only quads are supported")]
    NotQuad { line: usize, corners: usize },
    #[error("line {line}: bad vertex index {token:?}")]
    BadIndex { line: usize, token: String },
    #[error("line {line}: index {index} refers to no vertex ({vertex_count} available)")]
    IndexOutOfRange {
        line: usize,
        index: i64,
        vertex_count: usize,
    },
    #[error("invalid quad mesh: {0}")]
    Mesh(#[from] MeshError),
}

impl From<ObjDefect> for ObjError {
    fn from(defect: ObjDefect) -> Self {
        match defect {
            ObjDefect::NotUtf8 { line } => ObjError::NotUtf8 { line },
            ObjDefect::NotAsciiSpace { line, space } => ObjError::NotAsciiSpace { line, space },
            ObjDefect::VertexNotNumber { line, .. }
            | ObjDefect::VertexTooFewValues { line, .. } => ObjError::BadVertex { line },
            ObjDefect::VertexNotFinite { line, axis, value } => {
                ObjError::NonFiniteVertex { line, axis, value }
            }
            ObjDefect::TooManyVertices { count } => {
                ObjError::Mesh(MeshError::TooManyVertices { count })
            }
            ObjDefect::ReferenceNotIndex { line, token }
            | ObjDefect::ReferenceZero { line, token }
            | ObjDefect::ReferenceTooLarge { line, token, .. } => {
                ObjError::BadIndex { line, token }
            }
            ObjDefect::ReferenceBeforeFirst {
                line,
                index,
                defined,
            } => ObjError::IndexOutOfRange {
                line,
                index,
                vertex_count: defined,
            },
            ObjDefect::FaceCorners { line, count } => ObjError::NotQuad {
                line,
                corners: count,
            },
            ObjDefect::ReferenceOutOfRange {
                line,
                index,
                vertices,
            } => ObjError::IndexOutOfRange {
                line,
                index,
                vertex_count: vertices,
            },
        }
    }
}

/// Parses an OBJ quad mesh. Positive indices may refer to any vertex of the file,
/// negative ones count back from the last vertex defined before the face.
pub fn parse_obj(bytes: &[u8]) -> Result<QuadMesh, ObjError> {
    let read = parse_obj_polygons(bytes, Corners::Exactly(4))?;
    let faces = read
        .polygons()
        .map(|(_, quad)| [quad[0], quad[1], quad[2], quad[3]])
        .collect();
    Ok(QuadMesh::new(read.vertices, faces)?)
}

/// Writes `mesh` as OBJ text (`v` lines with round-trip exact coordinates, then
/// 1-based `f` lines).
pub fn write_obj(mesh: &QuadMesh) -> Vec<u8> {
    let mut out = String::new();
    for p in mesh.vertices() {
        // Writing to a String cannot fail.
        let _ = writeln!(out, "v {} {} {}", p[0], p[1], p[2]);
    }
    for f in mesh.faces() {
        let _ = writeln!(out, "f {} {} {} {}", f[0] + 1, f[1] + 1, f[2] + 1, f[3] + 1);
    }
    out.into_bytes()
}
