//! Why bytes could not be read as a cloud or a surrogate: every message names the
//! problem and, where there is one, the line or byte offset it was found at.

use shroud_surrogate::SurrogateDefect;
use thiserror::Error;

/// A parse or validation failure of one of the formats in [`crate::format`].
#[derive(Debug, Error, Clone, PartialEq)]
pub enum FormatError {
    // --- PLY -------------------------------------------------------------------
    #[error("not a PLY file: it must start with the line 'ply'")]
    PlyMissingMagic,
    #[error("PLY header line {line}: unknown format '{found}' (expected ascii, binary_little_endian or binary_big_endian)")]
    PlyUnknownFormat { line: usize, found: String },
    #[error("PLY header line {line} is malformed: {reason}")]
    PlyMalformedHeader { line: usize, reason: String },
    #[error("PLY header has no 'format' line")]
    PlyMissingFormat,
    #[error("PLY header never ends: no 'end_header' line")]
    PlyMissingEndHeader,
    #[error("PLY file has no 'vertex' element")]
    PlyNoVertexElement,
    #[error("PLY vertex element has no '{axis}' property")]
    PlyMissingCoordinate { axis: char },
    #[error("PLY header line {line}: unsupported property type '{name}'")]
    PlyUnsupportedType { line: usize, name: String },
    #[error("PLY body is truncated: expected {expected} vertices, got {got} (reading stopped at byte offset {offset})")]
    PlyTruncatedBody {
        expected: usize,
        got: usize,
        offset: usize,
    },
    #[error("PLY body line {line}: '{token}' is not a number")]
    PlyBadAsciiNumber { line: usize, token: String },
    #[error("PLY element '{element}' record {record}: invalid list length {length}")]
    PlyBadListLength {
        element: String,
        record: usize,
        length: f64,
    },
    #[error("PLY body line {line}: {reason}")]
    PlyBadAsciiRecord { line: usize, reason: String },

    // --- PCD (PCL's point cloud data) ----------------------------------------------
    #[error("PCD header line {line} is malformed: {reason}")]
    PcdMalformedHeader { line: usize, reason: String },
    #[error("PCD header never ends: no 'DATA' line")]
    PcdMissingData,
    #[error("PCD header has no '{keyword}' line")]
    PcdMissingKeyword { keyword: &'static str },
    #[error("PCD header line {line}: unknown DATA '{found}' (expected ascii, binary or binary_compressed)")]
    PcdUnknownData { line: usize, found: String },
    #[error(
        "PCD header line {line}: {keyword} has {got} values but FIELDS names {expected} fields"
    )]
    PcdFieldCountMismatch {
        line: usize,
        keyword: &'static str,
        got: usize,
        expected: usize,
    },
    #[error("PCD header line {line}: field '{field}' has TYPE {kind} with SIZE {size}, which PCD does not define (I and U take 1, 2, 4 or 8 bytes, F 4 or 8)")]
    PcdUnsupportedType {
        line: usize,
        field: String,
        kind: String,
        size: usize,
    },
    #[error("PCD header has no '{axis}' field")]
    PcdMissingCoordinate { axis: char },
    #[error("PCD field '{field}' has COUNT {count}: shroud reads it as a single value per point")]
    PcdFieldNotScalar { field: String, count: usize },
    #[error("PCD header: POINTS {points} is not WIDTH {width} x HEIGHT {height}")]
    PcdPointsMismatch {
        points: usize,
        width: usize,
        height: usize,
    },
    #[error("PCD header: {what} is too large to address")]
    PcdAbsurdSize { what: String },
    #[error("PCD body is truncated: point {point} field '{field}' needs {needed} bytes at offset {offset}, only {available} remain")]
    PcdTruncatedBody {
        point: usize,
        field: String,
        needed: usize,
        offset: usize,
        available: usize,
    },
    #[error("PCD body holds {got} of the {expected} points the header announces (reading stopped at byte offset {offset})")]
    PcdMissingPoints {
        expected: usize,
        got: usize,
        offset: usize,
    },
    #[error("PCD body has {count} bytes after its last point (POINTS {points}), from byte offset {offset}, and they are not zero padding")]
    PcdTrailingBytes {
        count: usize,
        points: usize,
        offset: usize,
    },
    #[error("PCD body line {line} (point {point}): {reason}")]
    PcdBadAsciiRecord {
        line: usize,
        point: usize,
        reason: String,
    },
    #[error("PCD body line {line} (point {point}): field '{field}' is '{token}', not a number")]
    PcdBadAsciiNumber {
        line: usize,
        point: usize,
        field: String,
        token: String,
    },
    #[error("PCD binary_compressed body at byte offset {offset}: {reason}")]
    PcdBadCompressedBody { offset: usize, reason: String },
    #[error("a binary_compressed PCD body of {bytes} bytes is more than the {max} bytes shroud reads back; write binary instead")]
    PcdTooLargeToCompress { bytes: usize, max: usize },
    #[error("all {count} points of the PCD file are invalid (NaN coordinates)")]
    PcdAllPointsInvalid { count: usize },

    // --- triangle meshes (OBJ, PLY faces) ----------------------------------------
    #[error(
        "not a triangle mesh: neither a PLY file nor UTF-8 OBJ text (invalid UTF-8 on line {line})"
    )]
    ObjNotUtf8 { line: usize },
    #[error("OBJ line {line}: {reason}")]
    ObjBadLine { line: usize, reason: String },
    #[error("PLY element '{element}' is truncated: expected {expected} records, got {got} (reading stopped at byte offset {offset})")]
    PlyTruncatedElement {
        element: String,
        expected: usize,
        got: usize,
        offset: usize,
    },
    #[error("PLY file has no 'face' element with records: it is a point cloud, not a mesh")]
    PlyNoFaceElement,
    #[error("PLY face element has no list property of vertex indices")]
    PlyNoFaceIndices,
    #[error("{location}: vertex index {index} is out of range (the mesh has {vertices} vertices)")]
    MeshIndexOutOfRange {
        location: String,
        index: i64,
        vertices: usize,
    },
    #[error("{location}: vertex index {value} is not a non-negative integer")]
    MeshBadIndex { location: String, value: f64 },
    #[error("{location}: a face needs at least 3 vertices, this one has {count}")]
    MeshDegenerateFace { location: String, count: usize },
    #[error("{location}: coordinate {axis} is {value}, must be finite")]
    MeshNonFiniteVertex {
        location: String,
        axis: char,
        value: f64,
    },
    #[error("the mesh has {count} vertices, more than the {max} that u32 indices address")]
    MeshTooManyVertices { count: usize, max: usize },
    #[error("the mesh has no vertices")]
    MeshNoVertices,
    #[error("the mesh has {vertices} vertices but no faces")]
    MeshNoFaces { vertices: usize },

    // --- XYZ / CSV ---------------------------------------------------------------
    #[error("line {line}: {reason}")]
    XyzBadLine { line: usize, reason: String },
    #[error("the file holds no points")]
    NoPoints,

    // --- surrogate files ---------------------------------------------------------
    #[error("surrogate JSON is malformed: {0}")]
    SurrogateJson(String),
    #[error("not a shroud surrogate: format tag is '{found}', expected 'shroud-surrogate'")]
    WrongFormatTag { found: String },
    #[error("unsupported surrogate format version {found} (this build reads version {supported})")]
    UnsupportedVersion { found: u64, supported: u32 },
    #[error("not a binary shroud surrogate: the file does not start with SHRDSURR")]
    BadMagic,
    #[error("binary surrogate is truncated: {what} needs {needed} bytes at offset {offset}, only {available} remain")]
    Truncated {
        what: &'static str,
        offset: usize,
        needed: u64,
        available: usize,
    },
    #[error("binary surrogate has {count} unexpected bytes after the checksum")]
    TrailingBytes { count: usize },
    #[error("binary surrogate checksum mismatch: stored {stored:#010x}, computed {computed:#010x} (the file is corrupted)")]
    ChecksumMismatch { stored: u32, computed: u32 },
    #[error("binary surrogate field {what} at offset {offset} has invalid value {value}")]
    BadField {
        what: &'static str,
        offset: usize,
        value: u64,
    },
    #[error("invalid surrogate: {0}")]
    InvalidSurrogate(#[from] SurrogateDefect),
}
