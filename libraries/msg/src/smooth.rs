//! Smooth-fit messages (paper 004): the G1 biquintic patches a `smooth` node
//! fitted to one cloud, their domain, and the error measures of eq. (28).

use super::blob::{bytes_to_f64s, decode, encode};
use super::error::MessageError;
use super::{check_finite, check_version, SCHEMA_VERSION};
use serde::{Deserialize, Serialize};

/// Coefficients of one biquintic patch (6 x 6, paper 004, Section 3).
pub const COEFFICIENTS_PER_PATCH: usize = 36;

/// Patches on the wire. `kind` is `graph` (value = z over the planar domain
/// point), `radial` (value = distance from the origin along the domain
/// point's direction) or `parametric` (value = the surface point, dim 3).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SmoothPatchesMessage {
    pub version: u16,
    pub source_stamp_ns: u64,
    pub source_sequence: u64,
    pub source: String,
    pub kind: String,
    pub dim: u32,
    /// Domain vertices, little-endian f64 x, y, z.
    #[serde(with = "serde_bytes")]
    pub vertices: Vec<u8>,
    /// Domain quads, little-endian u32, four per face.
    #[serde(with = "serde_bytes")]
    pub quads: Vec<u8>,
    /// `faces * 36 * dim` little-endian f64, as in the JSON patches of `docs/formats.md`.
    #[serde(with = "serde_bytes")]
    pub coefficients: Vec<u8>,
    pub functions: u64,
    pub lambda: f64,
    /// Points fitted, and points of the cloud outside the domain (skipped).
    pub points: u64,
    pub outside: u64,
    pub error_min: f64,
    pub error_max: f64,
    pub error_rmse: f64,
    pub fit_ns: u64,
}

impl SmoothPatchesMessage {
    pub fn to_bytes(&self) -> Result<Vec<u8>, MessageError> {
        encode(self)
    }

    /// Decodes and validates: version, kind, blob lengths against each other,
    /// finite numbers, quad indices within the vertices.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, MessageError> {
        let msg: Self = decode(bytes)?;
        check_version("smooth patches", msg.version, SCHEMA_VERSION)?;
        let dim = match msg.kind.as_str() {
            "graph" | "radial" => 1,
            "parametric" => 3,
            other => {
                return Err(MessageError::Invalid {
                    field: "kind",
                    reason: format!("{other:?} is not graph, radial or parametric"),
                })
            }
        };
        if msg.dim != dim {
            return Err(MessageError::Invalid {
                field: "dim",
                reason: format!("{} for a {} fit, which has {dim}", msg.dim, msg.kind),
            });
        }
        let vertices = bytes_to_f64s(&msg.vertices, "vertices")?;
        let coefficients = bytes_to_f64s(&msg.coefficients, "coefficients")?;
        if !vertices.len().is_multiple_of(3) || !msg.quads.len().is_multiple_of(16) {
            return Err(MessageError::BlobLength {
                field: "vertices or quads",
                len: vertices.len(),
                unit: 3,
            });
        }
        let faces = msg.quads.len() / 16;
        let expected = faces * COEFFICIENTS_PER_PATCH * msg.dim as usize;
        if coefficients.len() != expected {
            return Err(MessageError::Count {
                field: "coefficients",
                found: coefficients.len(),
                expected,
            });
        }
        let n_vertices = (vertices.len() / 3) as u32;
        let (quads, _) = msg.quads.as_chunks::<4>();
        if let Some(index) = quads
            .iter()
            .position(|q| u32::from_le_bytes(*q) >= n_vertices)
        {
            return Err(MessageError::Invalid {
                field: "quads",
                reason: format!("index {index} refers past the {n_vertices} vertices"),
            });
        }
        check_finite(
            "lambda, errors",
            &[msg.lambda, msg.error_min, msg.error_max, msg.error_rmse],
        )?;
        check_finite("vertices", &vertices)?;
        check_finite("coefficients", &coefficients)?;
        Ok(msg)
    }
}
