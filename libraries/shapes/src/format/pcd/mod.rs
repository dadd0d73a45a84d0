//! PCD point clouds, the Point Cloud Data format of PCL (`pcl::PCDReader` and
//! `pcl::PCDWriter`, format v0.7): `ascii`, `binary` and `binary_compressed`
//! bodies; x, y, z of any field type and an optional intensity, in any field
//! order; every other field (rgb, normals, labels, `_` padding, COUNT > 1
//! arrays) is skipped. Points with a NaN coordinate, PCL's marker of invalid
//! points in organised clouds, are left out and counted, as PCL's
//! `removeNaNFromPointCloud` does.

mod ascii_body;
mod binary_body;
mod columns;
mod compressed_body;
mod fields;
mod header;
mod layout;
mod lzf;
#[cfg(test)]
mod proptests;
mod raw_header;
#[cfg(test)]
mod tests;
mod write;

pub use header::has_pcd_header;
pub use write::write_pcd;

use super::ply::PlyCloud;
use super::FormatError;
use header::parse_header;
use layout::PointLayout;

/// How a PCD body is encoded (the header's `DATA` line).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PcdEncoding {
    /// One line of space-separated values per point.
    Ascii,
    /// Packed little-endian records, one per point.
    #[default]
    Binary,
    /// The records' fields one after the other (all x, then all y...),
    /// LZF-compressed, after the compressed and uncompressed sizes (u32 each).
    BinaryCompressed,
}

impl PcdEncoding {
    /// Every encoding, in the order of [`PcdEncoding::name`]'s documentation.
    pub const ALL: [Self; 3] = [Self::Ascii, Self::Binary, Self::BinaryCompressed];

    /// The name on the `DATA` line: `ascii`, `binary` or `binary_compressed`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Ascii => "ascii",
            Self::Binary => "binary",
            Self::BinaryCompressed => "binary_compressed",
        }
    }

    /// The encoding a `DATA` name stands for (exactly as PCL writes it).
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|e| e.name() == name)
    }
}

/// Parses a PCD file. Coordinates and intensity of any type are converted to
/// f32; points with a NaN coordinate are left out and counted in
/// [`PlyCloud::skipped_invalid`].
pub fn parse_pcd(bytes: &[u8]) -> Result<PlyCloud, FormatError> {
    let header = parse_header(bytes)?;
    let layout = PointLayout::of(&header.fields)?;
    match header.encoding {
        PcdEncoding::Ascii => ascii_body::read_points(bytes, &header, &layout),
        PcdEncoding::Binary => binary_body::read_points(bytes, &header, &layout),
        PcdEncoding::BinaryCompressed => compressed_body::read_points(bytes, &header, &layout),
    }
}

/// Checks the bytes after a binary body, from `end` on: PCL pads the files it
/// writes with zero bytes (PCL 1.13 rounds them up to whole memory pages), so
/// zeros are accepted; anything else would be points the header does not count.
fn check_padding(bytes: &[u8], end: usize, points: usize) -> Result<(), FormatError> {
    let rest = bytes.get(end..).unwrap_or_default();
    if rest.iter().all(|&b| b == 0) {
        Ok(())
    } else {
        Err(FormatError::PcdTrailingBytes {
            count: rest.len(),
            points,
            offset: end,
        })
    }
}

/// Adds a point unless a coordinate is NaN, which PCL uses to mark an invalid
/// point (the point is then counted as skipped).
fn push_point(cloud: &mut PlyCloud, xyz: [f64; 3], intensity: Option<f64>) {
    if xyz.iter().any(|v| v.is_nan()) {
        cloud.skipped_invalid += 1;
    } else {
        cloud.push(xyz.map(|v| v as f32), intensity.map(|v| v as f32));
    }
}
