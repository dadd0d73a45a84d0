//! Smooth fits on the wire (paper 004): a fitted [`SmoothSurface`] over its
//! quad domain to a [`SmoothPatchesMessage`]. The message type lives in
//! `shroud_msg`; the conversion lives here, beside the fitter.

use super::{FitErrors, SmoothSurface};
use crate::mesh::QuadMesh;
use shroud_msg::{f64s_to_bytes, SmoothPatchesMessage, SCHEMA_VERSION};

/// What [`patches_message`] needs besides the surface.
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

/// The message of `surface`, fitted over `domain`, with what the fit node reports.
pub fn patches_message(
    domain: &QuadMesh,
    surface: &SmoothSurface,
    r: &SmoothFitReport<'_>,
) -> SmoothPatchesMessage {
    let vertices: Vec<f64> = domain.vertices().iter().flatten().copied().collect();
    SmoothPatchesMessage {
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

/// A small graph fit over the triangle test mesh, for tests of consumers.
/// Public only for the tests of other crates.
#[doc(hidden)]
pub fn sample_patches_message() -> SmoothPatchesMessage {
    use super::{Sample, SmoothFitter};
    use crate::mesh::{triangle_mesh, G1Domain};
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
    patches_message(&mesh, &surface, &report)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn message() -> SmoothPatchesMessage {
        sample_patches_message()
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
