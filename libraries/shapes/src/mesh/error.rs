//! Why a list of vertices and quads is not a valid quad mesh.

use thiserror::Error;

#[derive(Debug, Error, Clone, PartialEq)]
pub enum MeshError {
    #[error("the mesh has no faces")]
    NoFaces,
    #[error("vertex {vertex} has a non-finite coordinate")]
    NonFiniteVertex { vertex: usize },
    #[error("face {face} corner {corner} refers to vertex {index} but there are {vertex_count} vertices")]
    IndexOutOfRange {
        face: usize,
        corner: usize,
        index: u32,
        vertex_count: usize,
    },
    #[error("face {face} is degenerate: vertex {vertex} appears more than once")]
    DegenerateFace { face: usize, vertex: u32 },
    #[error(
        "edge {a}-{b} is shared by more than two faces (faces {first}, {second}, {third}, ...)"
    )]
    NonManifoldEdge {
        a: u32,
        b: u32,
        first: usize,
        second: usize,
        third: usize,
    },
    #[error("edge {a}->{b} is used in the same direction by faces {first} and {second} (inconsistent orientation)")]
    InconsistentOrientation {
        a: u32,
        b: u32,
        first: usize,
        second: usize,
    },
    #[error("vertex {vertex} is not used by any face")]
    UnusedVertex { vertex: usize },
    #[error("the faces around vertex {vertex} form more than one fan (non-manifold vertex)")]
    NonManifoldVertex { vertex: usize },
    #[error("not supported yet: {what}")]
    Unsupported { what: &'static str },
    #[error("the mesh has {count} vertices, more than u32 indices can address")]
    TooManyVertices { count: usize },
}
