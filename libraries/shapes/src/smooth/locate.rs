//! Parameters of points over a planar quad-mesh domain (the paper's graphs
//! over M_T and the hexagon): the face that contains a point and its (u, v)
//! by inverting the face's bilinear map, with faces bucketed on a grid.

use super::error::SmoothError;
use super::sample::Sample;
use crate::mesh::QuadMesh;

/// Finds the face and bilinear parameters of points of the plane z = 0.
#[derive(Debug, Clone)]
pub struct PlanarLocator {
    quads: Vec<[[f64; 2]; 4]>,
    origin: [f64; 2],
    cell: f64,
    cols: usize,
    rows: usize,
    buckets: Vec<Vec<usize>>,
}

impl PlanarLocator {
    /// The mesh must lie in z = 0 (within 1e-9 of its size).
    pub fn new(mesh: &QuadMesh) -> Result<Self, SmoothError> {
        let v = mesh.vertices();
        if let Some(vertex) = non_planar_vertex(mesh) {
            return Err(SmoothError::NotPlanar {
                vertex,
                z: v[vertex][2],
            });
        }
        let quads: Vec<[[f64; 2]; 4]> = mesh
            .faces()
            .iter()
            .map(|f| f.map(|i| [v[i as usize][0], v[i as usize][1]]))
            .collect();
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in v {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let side = ((quads.len() as f64).sqrt().ceil() as usize).max(1);
        let cell = ((hi[0] - lo[0]).max(hi[1] - lo[1]) / side as f64).max(f64::MIN_POSITIVE);
        let cols = ((hi[0] - lo[0]) / cell).floor() as usize + 1;
        let rows = ((hi[1] - lo[1]) / cell).floor() as usize + 1;
        let mut buckets = vec![Vec::new(); cols * rows];
        for (f, q) in quads.iter().enumerate() {
            let (mut a, mut b) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
            for p in q {
                for k in 0..2 {
                    a[k] = a[k].min(p[k]);
                    b[k] = b[k].max(p[k]);
                }
            }
            let c0 = ((a[0] - lo[0]) / cell).floor() as usize;
            let c1 = (((b[0] - lo[0]) / cell).floor() as usize).min(cols - 1);
            let r0 = ((a[1] - lo[1]) / cell).floor() as usize;
            let r1 = (((b[1] - lo[1]) / cell).floor() as usize).min(rows - 1);
            for r in r0..=r1 {
                for c in c0..=c1 {
                    buckets[r * cols + c].push(f);
                }
            }
        }
        Ok(Self {
            quads,
            origin: lo,
            cell,
            cols,
            rows,
            buckets,
        })
    }

    /// The sample of `(x, y)`, or `None` outside the domain.
    pub fn locate(&self, x: f64, y: f64) -> Option<Sample> {
        if !(x.is_finite() && y.is_finite()) {
            return None;
        }
        let c = ((x - self.origin[0]) / self.cell).floor();
        let r = ((y - self.origin[1]) / self.cell).floor();
        if c < 0.0 || r < 0.0 || c as usize >= self.cols || r as usize >= self.rows {
            return None;
        }
        let bucket = &self.buckets[r as usize * self.cols + c as usize];
        bucket.iter().find_map(|&f| {
            let (u, v) = inverse_bilinear(&self.quads[f], x, y)?;
            Some(Sample { face: f, u, v })
        })
    }

    /// Samples of many points; the first point outside the domain is an error.
    pub fn locate_all(&self, xy: &[[f64; 2]]) -> Result<Vec<Sample>, SmoothError> {
        xy.iter()
            .enumerate()
            .map(|(index, p)| {
                self.locate(p[0], p[1]).ok_or(SmoothError::OutsideDomain {
                    index,
                    x: p[0],
                    y: p[1],
                })
            })
            .collect()
    }
}

/// Whether `mesh` lies in the plane z = 0 (within 1e-9 of its size, or of 1
/// for meshes smaller than that): a domain for graphs z(x, y).
pub fn is_planar(mesh: &QuadMesh) -> bool {
    non_planar_vertex(mesh).is_none()
}

fn non_planar_vertex(mesh: &QuadMesh) -> Option<usize> {
    let v = mesh.vertices();
    let size = v
        .iter()
        .flat_map(|p| [p[0].abs(), p[1].abs()])
        .fold(1.0f64, f64::max);
    v.iter().position(|p| p[2].abs() > 1e-9 * size)
}

/// `(u, v)` with `bilinear(q, u, v) = (x, y)` inside the unit square (up to a
/// small tolerance, then clamped), by Newton's method.
fn inverse_bilinear(q: &[[f64; 2]; 4], x: f64, y: f64) -> Option<(f64, f64)> {
    let size = q
        .iter()
        .flat_map(|p| [(p[0] - q[0][0]).abs(), (p[1] - q[0][1]).abs()])
        .fold(0.0f64, f64::max);
    let (mut u, mut v) = (0.5, 0.5);
    for _ in 0..50 {
        let f = residual(q, u, v, x, y);
        if f[0].abs().max(f[1].abs()) <= 1e-12 * size {
            let tol = 1e-9;
            let inside = |t: f64| (-tol..=1.0 + tol).contains(&t);
            return (inside(u) && inside(v)).then(|| (u.clamp(0.0, 1.0), v.clamp(0.0, 1.0)));
        }
        // Columns of the Jacobian: d/du and d/dv.
        let du = [
            (1.0 - v) * (q[1][0] - q[0][0]) + v * (q[2][0] - q[3][0]),
            (1.0 - v) * (q[1][1] - q[0][1]) + v * (q[2][1] - q[3][1]),
        ];
        let dv = [
            (1.0 - u) * (q[3][0] - q[0][0]) + u * (q[2][0] - q[1][0]),
            (1.0 - u) * (q[3][1] - q[0][1]) + u * (q[2][1] - q[1][1]),
        ];
        let det = du[0] * dv[1] - du[1] * dv[0];
        if det.is_nan() || det.abs() <= 1e-300 {
            return None;
        }
        u -= (f[0] * dv[1] - f[1] * dv[0]) / det;
        v -= (du[0] * f[1] - du[1] * f[0]) / det;
        if !(u.is_finite() && v.is_finite()) {
            return None;
        }
    }
    // No convergence: the point is not on this face (or the face is folded).
    None
}

/// `bilinear(q, u, v) - (x, y)`.
fn residual(q: &[[f64; 2]; 4], u: f64, v: f64, x: f64, y: f64) -> [f64; 2] {
    let w = [(1.0 - u) * (1.0 - v), u * (1.0 - v), u * v, (1.0 - u) * v];
    let mut f = [-x, -y];
    for (corner, weight) in q.iter().zip(w) {
        f[0] += weight * corner[0];
        f[1] += weight * corner[1];
    }
    f
}
