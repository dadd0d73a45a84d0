//! Smooth-fit messages (paper 004): the G1 biquintic patches a `smooth` node
//! fitted to one cloud, their domain, and the error measures of eq. (28).

use super::blob::{bytes_to_f64s, decode, encode, f64s_to_bytes};
use super::error::MessageError;
use super::{check_finite, check_version, SCHEMA_VERSION};
use crate::mesh::{QuadMesh, PATCH_COEFFICIENTS};
use crate::smooth::{FitErrors, SmoothSurface};
use serde::{Deserialize, Serialize};

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
    /// `faces * 36 * dim` little-endian f64, as in the JSON patches of FORMATS.md.
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

/// What [`SmoothPatchesMessage::new`] needs besides the surface.
#[derive(Debug, Clone, Copy)]
pub struct SmoothFitReport<'a> {
    pub source_stamp_ns: u64,
    pub source_sequence: u64,
    pub source: &'a str,
    pub kind: &'a str,
    pub functions: usize,
    pub lambda: f64,
    pub points: usize,
    pub outside: usize,
    pub errors: FitErrors,
    pub fit_ns: u64,
}

impl SmoothPatchesMessage {
    pub fn new(domain: &QuadMesh, surface: &SmoothSurface, r: &SmoothFitReport<'_>) -> Self {
        let vertices: Vec<f64> = domain.vertices().iter().flatten().copied().collect();
        Self {
            version: SCHEMA_VERSION,
            source_stamp_ns: r.source_stamp_ns,
            source_sequence: r.source_sequence,
            source: r.source.to_owned(),
            kind: r.kind.to_owned(),
            dim: surface.dim as u32,
            vertices: f64s_to_bytes(&vertices),
            quads: domain
                .faces()
                .iter()
                .flatten()
                .flat_map(|i| i.to_le_bytes())
                .collect(),
            coefficients: f64s_to_bytes(&surface.coefficients),
            functions: r.functions as u64,
            lambda: r.lambda,
            points: r.points as u64,
            outside: r.outside as u64,
            error_min: r.errors.min,
            error_max: r.errors.max,
            error_rmse: r.errors.rmse,
            fit_ns: r.fit_ns,
        }
    }

    pub fn to_bytes(&self) -> Result<Vec<u8>, MessageError> {
        encode(self)
    }

    /// Decodes and validates: version, kind, blob lengths against each other,
    /// finite numbers, quad indices within the vertices.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, MessageError> {
        let msg: Self = decode(bytes)?;
        check_version(msg.version)?;
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
        let expected = faces * PATCH_COEFFICIENTS * msg.dim as usize;
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

/// A small graph fit over the triangle test mesh, for tests of consumers.
#[cfg(test)]
pub(crate) fn sample_smooth_message() -> SmoothPatchesMessage {
    use crate::mesh::{triangle_mesh, G1Domain};
    use crate::smooth::{Sample, SmoothFitter};
    let mesh = triangle_mesh();
    let fitter = SmoothFitter::new(G1Domain::new(mesh.clone()).unwrap()).unwrap();
    let samples: Vec<Sample> = (0..300)
        .map(|k| Sample {
            face: k % 3,
            u: (k as f64 * 0.618).fract(),
            v: (k as f64 * 0.377).fract(),
        })
        .collect();
    let values: Vec<f64> = samples.iter().map(|s| s.u * s.v).collect();
    let surface = fitter.fit(&samples, &values, 1, 1e-6).unwrap();
    let report = SmoothFitReport {
        source_stamp_ns: 5,
        source_sequence: 6,
        source: "sim",
        kind: "graph",
        functions: fitter.basis.len(),
        lambda: 1e-6,
        points: 300,
        outside: 2,
        errors: surface.errors(&samples, &values),
        fit_ns: 7,
    };
    SmoothPatchesMessage::new(&mesh, &surface, &report)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn message() -> SmoothPatchesMessage {
        sample_smooth_message()
    }

    #[test]
    fn round_trips_and_refuses_inconsistent_messages() {
        let msg = message();
        let back = SmoothPatchesMessage::from_bytes(&msg.to_bytes().unwrap()).unwrap();
        assert_eq!(back, msg);
        let mut bad = msg.clone();
        bad.coefficients.truncate(8);
        assert!(SmoothPatchesMessage::from_bytes(&bad.to_bytes().unwrap()).is_err());
        let mut bad = msg.clone();
        bad.kind = "torus".into();
        assert!(SmoothPatchesMessage::from_bytes(&bad.to_bytes().unwrap()).is_err());
        // A parametric fit has three values per coefficient, not one.
        let mut bad = msg.clone();
        bad.kind = "parametric".into();
        assert!(SmoothPatchesMessage::from_bytes(&bad.to_bytes().unwrap()).is_err());
        let mut bad = msg.clone();
        bad.quads[0..4].copy_from_slice(&99u32.to_le_bytes());
        assert!(SmoothPatchesMessage::from_bytes(&bad.to_bytes().unwrap()).is_err());
        let mut bad = msg.clone();
        bad.coefficients[0..8].copy_from_slice(&f64::NAN.to_le_bytes());
        assert!(SmoothPatchesMessage::from_bytes(&bad.to_bytes().unwrap()).is_err());
        let mut bad = msg;
        bad.error_max = f64::NAN;
        let bytes = bad.to_bytes().unwrap();
        assert!(SmoothPatchesMessage::from_bytes(&bytes).is_err());
        for len in 0..bytes.len().min(400) {
            assert!(SmoothPatchesMessage::from_bytes(&bytes[..len]).is_err());
        }
    }
}
