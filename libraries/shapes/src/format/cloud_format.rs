//! Choosing the cloud parser: by file extension, or by sniffing the PLY magic
//! or a PCD header when the extension says nothing.

use super::pcd::{has_pcd_header, parse_pcd};
use super::ply::{has_ply_magic, parse_ply, PlyCloud};
use super::xyz::parse_xyz;
use super::FormatError;

/// A point cloud file format shroud reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CloudFormat {
    /// PLY, ASCII or binary (`.ply`).
    Ply,
    /// Whitespace-separated text (`.xyz`, `.txt`, `.asc`).
    Xyz,
    /// Comma-, semicolon- or tab-separated text (`.csv`, `.tsv`).
    Csv,
    /// PCL's Point Cloud Data, ascii, binary or binary_compressed (`.pcd`).
    Pcd,
}

impl CloudFormat {
    /// The format of a file extension, with or without its dot, in any case.
    pub fn from_extension(extension: &str) -> Option<Self> {
        let extension = extension
            .strip_prefix('.')
            .unwrap_or(extension)
            .to_ascii_lowercase();
        match extension.as_str() {
            "ply" => Some(Self::Ply),
            "xyz" | "txt" | "asc" => Some(Self::Xyz),
            "csv" | "tsv" => Some(Self::Csv),
            "pcd" => Some(Self::Pcd),
            _ => None,
        }
    }

    /// The format of a file name or path by its extension.
    pub fn from_file_name(name: &str) -> Option<Self> {
        let base = name.rsplit(['/', '\\']).next().unwrap_or(name);
        base.rsplit_once('.')
            .and_then(|(_, extension)| Self::from_extension(extension))
    }

    /// PLY if `bytes` start with the PLY magic line, PCD if they start with a PCD
    /// header (`#` comment lines, then `VERSION` or `FIELDS`), text otherwise.
    pub fn sniff(bytes: &[u8]) -> Self {
        if has_ply_magic(bytes) {
            Self::Ply
        } else if has_pcd_header(bytes) {
            Self::Pcd
        } else {
            Self::Xyz
        }
    }
}

/// Parses a cloud file in `format` (from [`CloudFormat::from_extension`], or
/// [`CloudFormat::sniff`] when the extension is unknown). A file without points
/// is [`FormatError::NoPoints`], whatever its format; a PCD file whose every
/// point is invalid (NaN) is [`FormatError::PcdAllPointsInvalid`].
pub fn parse_cloud(bytes: &[u8], format: CloudFormat) -> Result<PlyCloud, FormatError> {
    let cloud = match format {
        CloudFormat::Ply => parse_ply(bytes)?,
        CloudFormat::Pcd => parse_pcd(bytes)?,
        CloudFormat::Xyz | CloudFormat::Csv => PlyCloud {
            points: parse_xyz(bytes)?,
            ..PlyCloud::default()
        },
    };
    match (cloud.points.len(), cloud.skipped_invalid) {
        (0, 0) => Err(FormatError::NoPoints),
        (0, count) => Err(FormatError::PcdAllPointsInvalid { count }),
        _ => Ok(cloud),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::format::{write_pcd, write_ply_points, PcdEncoding};

    #[test]
    fn extensions_map_to_formats() {
        assert_eq!(CloudFormat::from_extension("PLY"), Some(CloudFormat::Ply));
        assert_eq!(CloudFormat::from_extension(".xyz"), Some(CloudFormat::Xyz));
        assert_eq!(CloudFormat::from_extension("tsv"), Some(CloudFormat::Csv));
        assert_eq!(CloudFormat::from_extension(".PCD"), Some(CloudFormat::Pcd));
        assert_eq!(CloudFormat::from_extension("las"), None);
        assert_eq!(
            CloudFormat::from_file_name("/data/scan.v2/Cloud.CSV"),
            Some(CloudFormat::Csv)
        );
        assert_eq!(CloudFormat::from_file_name("/data/scan.v2/cloud"), None);
    }

    #[test]
    fn unknown_extensions_are_sniffed() {
        let points = vec![[1.0, 2.0, 3.0], [4.0, 5.0, 6.5]];
        let ply = write_ply_points(&points, Some(&[0.5, 0.25]), false);
        let cloud = parse_cloud(&ply, CloudFormat::sniff(&ply)).unwrap();
        assert_eq!(cloud.points, points);
        assert_eq!(cloud.intensity, Some(vec![0.5, 0.25]));
        let text = b"1 2 3\n4 5 6.5\n";
        assert_eq!(CloudFormat::sniff(text), CloudFormat::Xyz);
        assert_eq!(
            parse_cloud(text, CloudFormat::sniff(text)).unwrap().points,
            points
        );
        let pcd = write_pcd(&points, None, PcdEncoding::Ascii).unwrap();
        assert_eq!(CloudFormat::sniff(&pcd), CloudFormat::Pcd);
        assert_eq!(
            parse_cloud(&pcd, CloudFormat::sniff(&pcd)).unwrap().points,
            points
        );
        let commented = b"# a note\n1 2 3\n";
        assert_eq!(CloudFormat::sniff(commented), CloudFormat::Xyz);
        let empty = write_ply_points(&[], None, true);
        assert_eq!(
            parse_cloud(&empty, CloudFormat::Ply),
            Err(FormatError::NoPoints)
        );
    }
}
