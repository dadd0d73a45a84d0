//! Fitted multipatches as quad meshes for viewing and export: each patch
//! sampled on a regular grid of its parameters and placed as a graph, a
//! radial surface or a parametric surface.

use super::fit::SmoothSurface;
use crate::mesh::{MeshError, QuadMesh};

impl SmoothSurface {
    /// A graph surface (`dim` 1 over a planar domain) as a quad mesh: each
    /// patch sampled on an `n x n` grid, at the domain's bilinear position with
    /// the fitted value as height. Patches keep their own border vertices.
    pub fn tessellate_graph(&self, domain: &QuadMesh, n: usize) -> Result<QuadMesh, MeshError> {
        self.tessellate(domain, n, |mut p, value| {
            p[2] = value[0];
            p
        })
    }

    /// A radial surface (`dim` 1 over a closed mesh around the origin, such as
    /// the cube-sphere) as a quad mesh: the fitted value is the distance from
    /// the origin along the domain point's direction.
    pub fn tessellate_radial(&self, domain: &QuadMesh, n: usize) -> Result<QuadMesh, MeshError> {
        self.tessellate(domain, n, |p, value| {
            let norm = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2])
                .sqrt()
                .max(f64::MIN_POSITIVE);
            p.map(|x| x / norm * value[0])
        })
    }

    /// A parametric surface (`dim` 3) as a quad mesh: the fitted points.
    pub fn tessellate_parametric(
        &self,
        domain: &QuadMesh,
        n: usize,
    ) -> Result<QuadMesh, MeshError> {
        self.tessellate(domain, n, |_, value| {
            [0, 1, 2].map(|d| value.get(d).copied().unwrap_or(0.0))
        })
    }

    fn tessellate(
        &self,
        domain: &QuadMesh,
        n: usize,
        place: impl Fn([f64; 3], &[f64]) -> [f64; 3],
    ) -> Result<QuadMesh, MeshError> {
        let n = n.max(1);
        let count = (n + 1)
            .checked_pow(2)
            .and_then(|per_face| per_face.checked_mul(domain.face_count()))
            .unwrap_or(usize::MAX);
        if count > u32::MAX as usize {
            return Err(MeshError::TooManyVertices { count });
        }
        let v = domain.vertices();
        let mut vertices = Vec::new();
        let mut quads = Vec::new();
        for (f, quad) in domain.faces().iter().enumerate() {
            let base = vertices.len() as u32;
            for b in 0..=n {
                for a in 0..=n {
                    let (u, w) = (a as f64 / n as f64, b as f64 / n as f64);
                    let weights = [(1.0 - u) * (1.0 - w), u * (1.0 - w), u * w, (1.0 - u) * w];
                    let mut p = [0.0; 3];
                    for (k, &corner) in quad.iter().enumerate() {
                        for (c, x) in p.iter_mut().enumerate() {
                            *x += weights[k] * v[corner as usize][c];
                        }
                    }
                    vertices.push(place(p, &self.evaluate(f, u, w)));
                }
            }
            let at = |a: usize, b: usize| base + (b * (n + 1) + a) as u32;
            for b in 0..n {
                for a in 0..n {
                    quads.push([at(a, b), at(a + 1, b), at(a + 1, b + 1), at(a, b + 1)]);
                }
            }
        }
        QuadMesh::new(vertices, quads)
    }
}
