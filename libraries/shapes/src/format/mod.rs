//! Every file format shroud reads or writes, as pure functions on bytes: point
//! clouds (PLY, PCD, XYZ/CSV/TSV), surrogates (JSON and compact binary, both validated
//! on read) and triangle meshes (OBJ, PLY) of the trimmed surfaces. The formats
//! are specified for users in `docs/formats.md`.

mod cloud_format;
mod crc32;
mod error;
mod mesh;
mod mesh_builder;
mod mesh_read;
mod obj;
mod pcd;
mod ply;
mod point_rows;
mod scalar;
mod surrogate_binary;
mod surrogate_json;
mod tessellate;
mod text_lines;
mod xyz;
#[cfg(test)]
mod xyz_proptests;

pub use cloud_format::{parse_cloud, CloudFormat};
pub use crc32::crc32;
pub use error::FormatError;
pub use mesh::TriangleMesh;
pub use mesh_read::parse_triangle_mesh;
pub(crate) use obj::{parse_obj_polygons, Corners, ObjDefect};
pub use pcd::{has_pcd_header, parse_pcd, write_pcd, PcdEncoding};
pub use ply::{has_ply_magic, parse_ply, write_ply_points, PlyCloud};
pub(crate) use ply::{write_ply_vertices, PlyProperty, PlyVertices};
pub use shroud_surrogate::{validate_surrogate, SurrogateDefect};
pub use surrogate_binary::{
    surrogate_from_binary, surrogate_to_binary, SURROGATE_BINARY_VERSION, SURROGATE_MAGIC,
};
pub use surrogate_json::{
    surrogate_from_json, surrogate_to_json, SURROGATE_FORMAT_TAG, SURROGATE_JSON_VERSION,
};
pub use tessellate::{tessellate, tessellate_all};
pub use xyz::{parse_xyz, write_xyz};
