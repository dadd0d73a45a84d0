//! PLY point clouds (`ascii`, `binary_little_endian`, `binary_big_endian`): the
//! `vertex` element's x, y, z of any scalar type and an optional intensity; every
//! other property and element is skipped. Triangle meshes (vertices plus the
//! `face` element) are read by [`parse_ply_mesh`] with the same record readers.
//! Point clouds, with any further per-vertex properties, are written by
//! [`write_ply_vertices`], and meshes by `TriangleMesh::to_ply` with the same header.

mod ascii_body;
mod binary_body;
mod header;
mod layout;
mod mesh;
#[cfg(test)]
mod proptests;
#[cfg(test)]
mod tests;
mod write;

pub use header::has_ply_magic;
pub(in crate::format) use mesh::parse_ply_mesh;
pub use write::write_ply_points;
pub(crate) use write::{write_ply_vertices, PlyProperty, PlyVertices};

use crate::format::FormatError;
use header::{parse_header, Encoding};
use layout::VertexLayout;
use shroud_geometry::PointCloud;

/// Points read from a cloud file, with the per-point intensity when the file has one.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PlyCloud {
    pub points: Vec<[f32; 3]>,
    /// One value per point, in the file's units (no rescaling).
    pub intensity: Option<Vec<f32>>,
    /// Points the file marks invalid that were left out: PCD points with a NaN
    /// coordinate (PCL's marker in organised clouds). Always 0 for PLY and text
    /// files, whose non-finite points are kept for validation to reject.
    pub skipped_invalid: usize,
}

impl PlyCloud {
    pub(in crate::format) fn with_capacity(points: usize, has_intensity: bool) -> Self {
        Self {
            points: Vec::with_capacity(points),
            intensity: has_intensity.then(|| Vec::with_capacity(points)),
            skipped_invalid: 0,
        }
    }

    pub(in crate::format) fn push(&mut self, point: [f32; 3], intensity: Option<f32>) {
        self.points.push(point);
        if let (Some(all), Some(value)) = (&mut self.intensity, intensity) {
            all.push(value);
        }
    }

    /// The points alone, as the fitters take them.
    pub fn into_point_cloud(self) -> PointCloud {
        PointCloud::new(self.points)
    }
}

/// Parses a PLY file. Coordinates of any type are converted to f32 (as
/// [`PointCloud`] stores them); elements after `vertex` are not read.
pub fn parse_ply(bytes: &[u8]) -> Result<PlyCloud, FormatError> {
    let header = parse_header(bytes)?;
    let layout = VertexLayout::of(&header)?;
    match header.encoding {
        Encoding::Ascii => ascii_body::read_vertices(bytes, &header, &layout),
        Encoding::BinaryLittleEndian => binary_body::read_vertices(bytes, &header, &layout, false),
        Encoding::BinaryBigEndian => binary_body::read_vertices(bytes, &header, &layout, true),
    }
}
