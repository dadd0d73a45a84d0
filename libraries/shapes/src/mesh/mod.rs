//! Quad meshes of arbitrary topology (Marsala, Mantzaflaris & Mourrain, "Point Cloud
//! Fitting by G1 Smooth Spline Functions", Sections 2-3): validated construction,
//! half-edge adjacency, the paper's vertex/edge classification, Catmull-Clark
//! refinement, OBJ bytes, and the dimension of the G1 space (Corollary 1).

mod catmull_clark;
mod classify;
mod dimension;
mod domains;
mod error;
mod g1_basis;
mod g1_constraints;
mod half_edge;
mod limit_surface;
mod obj;
mod polycube;
mod quad_mesh;

#[cfg(test)]
mod tests;

pub use catmull_clark::catmull_clark;
pub use classify::{classify, EdgeKind, MeshClassification, VertexKind};
pub use dimension::{G1Dimension, G1Domain};
pub use domains::{cube_mesh, hexagon_mesh, rectangle_mesh, triangle_mesh};
pub use error::MeshError;
pub use g1_basis::{BasisFunction, Feature, G1Basis};
pub use g1_constraints::{defect, g1_constraints, Row, PATCH_COEFFICIENTS};
pub use half_edge::HalfEdgeMesh;
pub use limit_surface::{
    child_parameters, coarsen_parameters, levels_within, limit_point, limit_position,
    parent_parameters, refine_mesh, refine_parameters, sample_limit_surface, LimitSample,
};
pub use obj::{parse_obj, write_obj, ObjError};
pub use polycube::{l_block, polycube, ring_block, step_block};
pub use quad_mesh::QuadMesh;
