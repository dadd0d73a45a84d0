//! A surrogate's surfaces as trimmed triangle meshes in single precision, the
//! form GPUs and viewers take (the tessellation itself is `format::tessellate`).

use shroud_shapes::format::tessellate;
use shroud_surrogate::{Certificate, Side, Surrogate};

/// One certified surface, tessellated over the kept (trimmed) cells.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceMesh {
    pub side: Side,
    /// World xyz per vertex.
    pub positions: Vec<[f32; 3]>,
    /// Three vertex indices per triangle, counter-clockwise seen from outside
    /// the sandwich.
    pub indices: Vec<u32>,
    pub certificate: Certificate,
}

/// Linear RGBA of each side: the upper surface blue, the lower amber, both
/// translucent so that the cloud between them shows.
pub fn surface_rgba(side: Side) -> [f64; 4] {
    match side {
        Side::Upper => [0.25, 0.55, 0.95, 0.45],
        Side::Lower => [0.95, 0.60, 0.20, 0.45],
    }
}

/// Every surface of `surrogate` (upper first), each kept trim triangle split
/// into `per_cell * per_cell` triangles.
pub fn surrogate_meshes(surrogate: &Surrogate, per_cell: usize) -> Vec<SurfaceMesh> {
    surrogate
        .surfaces()
        .filter_map(|safe| {
            let mesh = tessellate(surrogate, safe.side, per_cell)?;
            Some(SurfaceMesh {
                side: safe.side,
                positions: mesh.vertices.iter().map(|v| v.map(|x| x as f32)).collect(),
                indices: mesh.triangles.iter().flatten().copied().collect(),
                certificate: safe.certificate.clone(),
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use shroud_surrogate::{fit_surrogate, FitOptions, Sides};

    #[test]
    fn a_sandwich_gives_two_meshes_with_their_certificates() {
        let points: Vec<[f32; 3]> = (0..900)
            .map(|i| {
                let (x, y) = ((i % 30) as f32 * 0.1, (i / 30) as f32 * 0.1);
                [x, y, (x * 2.0).sin() * 0.3 + y * 0.1]
            })
            .collect();
        let options = FitOptions {
            cols: 6,
            rows: 6,
            sides: Sides::Sandwich,
            ..Default::default()
        };
        let s = fit_surrogate(&points, &options).unwrap();
        let meshes = surrogate_meshes(&s, 2);
        assert_eq!(meshes.len(), 2);
        assert_eq!((meshes[0].side, meshes[1].side), (Side::Upper, Side::Lower));
        for m in &meshes {
            assert!(!m.indices.is_empty() && m.indices.len() % 3 == 0);
            assert!(m.indices.iter().all(|&i| (i as usize) < m.positions.len()));
            assert_eq!(m.certificate.violations, 0);
            assert_eq!(m.certificate.points_checked, 900);
        }
        // The upper surface lies above the lower one at the same vertex.
        let z = |m: &SurfaceMesh| m.positions.iter().map(|p| p[2]).sum::<f32>();
        assert!(z(&meshes[0]) > z(&meshes[1]));
    }
}
