//! Wavefront OBJ quad meshes as bytes: `v x y z` and `f a b c d` lines (with optional
//! `/vt/vn` parts and negative indices), other statements ignored.

use std::fmt::Write as _;

use thiserror::Error;

use super::error::MeshError;
use super::quad_mesh::QuadMesh;

/// Why bytes are not an OBJ quad mesh. Line numbers start at 1.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ObjError {
    #[error("line {line}: not valid UTF-8")]
    NotUtf8 { line: usize },
    #[error("line {line}: a vertex needs three numeric coordinates")]
    BadVertex { line: usize },
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

/// Parses an OBJ quad mesh. Positive indices may refer to any vertex of the file,
/// negative ones count back from the last vertex defined before the face.
pub fn parse_obj(bytes: &[u8]) -> Result<QuadMesh, ObjError> {
    let mut vertices: Vec<[f64; 3]> = Vec::new();
    let mut faces: Vec<[u32; 4]> = Vec::new();
    let mut pending: Vec<(usize, i64)> = Vec::new(); // (line, positive index) to check
    for (i, raw) in bytes.split(|&b| b == b'\n').enumerate() {
        let line = i + 1;
        let text = std::str::from_utf8(raw).map_err(|_| ObjError::NotUtf8 { line })?;
        let text = text.split('#').next().unwrap_or("").trim();
        let mut tokens = text.split_whitespace();
        match tokens.next() {
            Some("v") => {
                let mut p = [0.0; 3];
                for c in &mut p {
                    *c = tokens
                        .next()
                        .and_then(|t| t.parse::<f64>().ok())
                        .ok_or(ObjError::BadVertex { line })?;
                }
                vertices.push(p);
            }
            Some("f") => {
                let corners: Vec<&str> = tokens.collect();
                if corners.len() != 4 {
                    return Err(ObjError::NotQuad {
                        line,
                        corners: corners.len(),
                    });
                }
                let mut face = [0u32; 4];
                for (slot, token) in face.iter_mut().zip(&corners) {
                    let index_text = token.split('/').next().unwrap_or("");
                    let bad = || ObjError::BadIndex {
                        line,
                        token: (*token).to_string(),
                    };
                    let index: i64 = index_text.parse().map_err(|_| bad())?;
                    let resolved = if index > 0 {
                        pending.push((line, index));
                        index - 1
                    } else if index < 0 {
                        let r = vertices.len() as i64 + index;
                        if r < 0 {
                            return Err(ObjError::IndexOutOfRange {
                                line,
                                index,
                                vertex_count: vertices.len(),
                            });
                        }
                        r
                    } else {
                        return Err(bad());
                    };
                    *slot = u32::try_from(resolved).map_err(|_| bad())?;
                }
                faces.push(face);
            }
            _ => {}
        }
    }
    for (line, index) in pending {
        if index as u64 > vertices.len() as u64 {
            return Err(ObjError::IndexOutOfRange {
                line,
                index,
                vertex_count: vertices.len(),
            });
        }
    }
    Ok(QuadMesh::new(vertices, faces)?)
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
