//! Parameters of directions over a cube-sphere quad mesh (paper 004, Example
//! 3): the face a direction passes through, by central projection, and its
//! (u, v) on that face's bilinear patch, for fitting radial functions
//! r(direction) over the sphere.

use super::error::SmoothError;
use super::sample::Sample;
use crate::mesh::{catmull_clark, cube_mesh, MeshError, QuadMesh};

/// The cube centred at the origin, refined `levels` times by Catmull-Clark,
/// its vertices projected onto the unit sphere (6 x 4^levels faces; 96 at 2).
pub fn cube_sphere(levels: usize) -> Result<QuadMesh, MeshError> {
    let cube = cube_mesh();
    let (vertices, faces) = cube.into_parts();
    let centred: Vec<[f64; 3]> = vertices.iter().map(|p| p.map(|x| x - 0.5)).collect();
    let mut mesh = QuadMesh::new(centred, faces)?;
    for _ in 0..levels {
        mesh = catmull_clark(&mesh)?;
    }
    let (vertices, faces) = mesh.into_parts();
    let projected = vertices
        .iter()
        .map(|p| {
            let n = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
            p.map(|x| x / n)
        })
        .collect();
    QuadMesh::new(projected, faces)
}

/// Central projection of directions onto a closed quad mesh around the origin.
#[derive(Debug, Clone)]
pub struct SphereLocator {
    quads: Vec<[[f64; 3]; 4]>,
    centres: Vec<[f64; 3]>,
}

impl SphereLocator {
    pub fn new(mesh: &QuadMesh) -> Self {
        let v = mesh.vertices();
        let quads: Vec<[[f64; 3]; 4]> = mesh
            .faces()
            .iter()
            .map(|f| f.map(|i| v[i as usize]))
            .collect();
        let centres = quads
            .iter()
            .map(|q| {
                let c = [0, 1, 2].map(|k| q.iter().map(|p| p[k]).sum::<f64>() / 4.0);
                let n = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2])
                    .sqrt()
                    .max(f64::MIN_POSITIVE);
                c.map(|x| x / n)
            })
            .collect();
        Self { quads, centres }
    }

    /// The sample where the ray from the origin along `d` meets the mesh.
    pub fn locate(&self, d: [f64; 3]) -> Option<Sample> {
        let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        if !(n.is_finite() && n > 0.0) {
            return None;
        }
        let d = d.map(|x| x / n);
        // Faces by how squarely they face the direction; the containing one is
        // among the first few.
        let mut order: Vec<(f64, usize)> = self
            .centres
            .iter()
            .enumerate()
            .map(|(f, c)| (-(c[0] * d[0] + c[1] * d[1] + c[2] * d[2]), f))
            .collect();
        let keep = order.len().min(8);
        order.select_nth_unstable_by(keep - 1, |a, b| a.0.total_cmp(&b.0));
        order.truncate(keep);
        order.sort_by(|a, b| a.0.total_cmp(&b.0));
        order.iter().find_map(|&(_, f)| {
            let (u, v) = central_projection(&self.quads[f], d)?;
            Some(Sample { face: f, u, v })
        })
    }

    /// Samples of many directions; a zero or non-finite one is an error.
    pub fn locate_all(&self, directions: &[[f64; 3]]) -> Result<Vec<Sample>, SmoothError> {
        directions
            .iter()
            .enumerate()
            .map(|(index, &d)| self.locate(d).ok_or(SmoothError::NoDirection { index }))
            .collect()
    }
}

/// `(u, v)` with `bilinear(q, u, v) = t d` for some `t > 0`, inside the unit
/// square, by Newton's method on the three unknowns.
fn central_projection(q: &[[f64; 3]; 4], d: [f64; 3]) -> Option<(f64, f64)> {
    let (mut u, mut v, mut t) = (0.5, 0.5, 1.0);
    for _ in 0..50 {
        let w = [(1.0 - u) * (1.0 - v), u * (1.0 - v), u * v, (1.0 - u) * v];
        let mut f = [0.0; 3];
        for k in 0..3 {
            f[k] = (0..4).map(|c| w[c] * q[c][k]).sum::<f64>() - t * d[k];
        }
        if f.iter().all(|x| x.abs() < 1e-13) {
            let tol = 1e-9;
            let inside = |s: f64| (-tol..=1.0 + tol).contains(&s);
            return (t > 0.0 && inside(u) && inside(v))
                .then(|| (u.clamp(0.0, 1.0), v.clamp(0.0, 1.0)));
        }
        let du = [0, 1, 2].map(|k| (1.0 - v) * (q[1][k] - q[0][k]) + v * (q[2][k] - q[3][k]));
        let dv = [0, 1, 2].map(|k| (1.0 - u) * (q[3][k] - q[0][k]) + u * (q[2][k] - q[1][k]));
        let dt = d.map(|x| -x);
        // Solve [du dv dt] s = f by Cramer's rule.
        let det = |a: [f64; 3], b: [f64; 3], c: [f64; 3]| {
            a[0] * (b[1] * c[2] - b[2] * c[1]) - b[0] * (a[1] * c[2] - a[2] * c[1])
                + c[0] * (a[1] * b[2] - a[2] * b[1])
        };
        let m = det(du, dv, dt);
        if m.is_nan() || m.abs() < 1e-300 {
            return None;
        }
        u -= det(f, dv, dt) / m;
        v -= det(du, f, dt) / m;
        t -= det(du, dv, f) / m;
        if !(u.is_finite() && v.is_finite() && t.is_finite()) || u.abs() > 10.0 || v.abs() > 10.0 {
            return None;
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_direction_lands_on_exactly_the_face_it_passes_through() {
        let mesh = cube_sphere(2).unwrap();
        assert_eq!(mesh.face_count(), 96);
        let locator = SphereLocator::new(&mesh);
        let v = mesh.vertices();
        for (f, quad) in mesh.faces().iter().enumerate() {
            for (u, w) in [(0.5, 0.5), (0.1, 0.8), (0.95, 0.05)] {
                let weights = [(1.0 - u) * (1.0 - w), u * (1.0 - w), u * w, (1.0 - u) * w];
                let p = [0, 1, 2].map(|k| {
                    (0..4)
                        .map(|c| weights[c] * v[quad[c] as usize][k])
                        .sum::<f64>()
                });
                let s = locator.locate(p).expect("on the mesh");
                assert_eq!(s.face, f);
                assert!((s.u - u).abs() < 1e-8 && (s.v - w).abs() < 1e-8);
            }
        }
        assert!(locator.locate([0.0; 3]).is_none());
        assert!(matches!(
            locator.locate_all(&[[1.0, 0.0, 0.0], [f64::NAN, 0.0, 0.0]]),
            Err(SmoothError::NoDirection { index: 1 })
        ));
    }
}
