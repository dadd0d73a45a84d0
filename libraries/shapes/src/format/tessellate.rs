//! Triangulating the trimmed surface of a surrogate for viewing and export.
//!
//! Each grid cell is split by both diagonals into four triangles with the cell
//! centre as apex (the trim triangles of Section 6, Figure 7); every kept triangle
//! is subdivided uniformly into `n x n` small triangles. All subdivision points lie
//! on one lattice of spacing `1 / (2n)` in `(s, t)`, so vertices shared by
//! neighbouring triangles and cells are found by their lattice key and stored once.

use super::mesh::TriangleMesh;
use shroud_surrogate::trim::{BOTTOM, LEFT, RIGHT, TOP};
use shroud_surrogate::{Side, Surrogate};
use std::collections::HashMap;

/// The four trim triangles of a cell as (bit, first corner, second corner) in
/// half-cell units from the cell's `(h, g)` corner; the third vertex is the centre
/// `(1, 1)`. Each is counter-clockwise in `(s, t)`.
const QUARTERS: [(u8, [i64; 2], [i64; 2]); 4] = [
    (BOTTOM, [0, 0], [2, 0]),
    (RIGHT, [2, 0], [2, 2]),
    (TOP, [2, 2], [0, 2]),
    (LEFT, [0, 2], [0, 0]),
];

/// The trimmed surface of `side` as a mesh, `per_cell` subdivisions along each
/// edge of each trim triangle (so `4 * per_cell^2` triangles per full cell; 0 is
/// taken as 1), or `None` if the surrogate has no surface on that side.
///
/// Normals face away from the cloud: toward `+w` (the viewer) for the upper
/// surface, toward `-w` for the lower one, so a sandwich is an outward-facing shell.
pub fn tessellate(surrogate: &Surrogate, side: Side, per_cell: usize) -> Option<TriangleMesh> {
    surrogate.surface(side)?;
    let mut lattice = LatticeMesh::new(surrogate, side, per_cell.max(1));
    let trim = &surrogate.trim;
    for g in 0..trim.cells_t {
        for h in 0..trim.cells_s {
            let bits = trim.bits.get(g * trim.cells_s + h).copied().unwrap_or(0);
            for (bit, a, b) in QUARTERS {
                if bits & bit != 0 {
                    let cell = [2 * h as i64, 2 * g as i64];
                    let corner = |c: [i64; 2]| [cell[0] + c[0], cell[1] + c[1]];
                    lattice.add_triangle(corner(a), corner(b), corner([1, 1]));
                }
            }
        }
    }
    Some(lattice.mesh)
}

/// Every surface the surrogate has (upper first), merged into one mesh.
pub fn tessellate_all(surrogate: &Surrogate, per_cell: usize) -> TriangleMesh {
    let mut mesh = TriangleMesh::default();
    for side in [Side::Upper, Side::Lower] {
        if let Some(part) = tessellate(surrogate, side, per_cell) {
            mesh.merge(&part);
        }
    }
    mesh
}

/// A mesh under construction whose vertices are keyed by lattice coordinates in
/// units of `1 / (2n)` parameter units.
struct LatticeMesh<'a> {
    surrogate: &'a Surrogate,
    side: Side,
    n: i64,
    index_of: HashMap<[i64; 2], u32>,
    mesh: TriangleMesh,
}

impl<'a> LatticeMesh<'a> {
    fn new(surrogate: &'a Surrogate, side: Side, n: usize) -> Self {
        Self {
            surrogate,
            side,
            n: n as i64,
            index_of: HashMap::new(),
            mesh: TriangleMesh::default(),
        }
    }

    /// Subdivides the triangle with corners `a, b, c` (half-cell units,
    /// counter-clockwise in `(s, t)`) into `n^2` triangles:
    /// `P(i, j) = a + i/n (b - a) + j/n (c - a)` for `i + j <= n`.
    fn add_triangle(&mut self, a: [i64; 2], b: [i64; 2], c: [i64; 2]) {
        let n = self.n;
        // In lattice units P(i, j) = n a + i (b - a) + j (c - a): all integers.
        let point =
            |i: i64, j: i64| [0, 1].map(|k| n * a[k] + i * (b[k] - a[k]) + j * (c[k] - a[k]));
        for j in 0..n {
            for i in 0..n - j {
                let (p, q, r) = (point(i, j), point(i + 1, j), point(i, j + 1));
                self.add_face(p, q, r);
                if i + 1 < n - j {
                    self.add_face(q, point(i + 1, j + 1), r);
                }
            }
        }
    }

    /// One small triangle, counter-clockwise in `(s, t)`; flipped for the lower
    /// side so that its normal faces `-w`.
    fn add_face(&mut self, p: [i64; 2], q: [i64; 2], r: [i64; 2]) {
        let face = [self.vertex(p), self.vertex(q), self.vertex(r)];
        self.mesh.triangles.push(match self.side {
            Side::Upper => face,
            Side::Lower => [face[0], face[2], face[1]],
        });
    }

    fn vertex(&mut self, key: [i64; 2]) -> u32 {
        if let Some(&index) = self.index_of.get(&key) {
            return index;
        }
        let scale = 1.0 / (2 * self.n) as f64;
        let (s, t) = (key[0] as f64 * scale, key[1] as f64 * scale);
        let point = self
            .surrogate
            .world_point(self.side, s, t)
            .unwrap_or_default();
        let index = self.mesh.vertices.len() as u32;
        self.mesh.vertices.push(point.to_array());
        self.index_of.insert(key, index);
        index
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;
    use shroud_surrogate::samples::fitted;
    use shroud_surrogate::trim::triangle_of;
    use shroud_surrogate::DomainLocate;
    use shroud_surrogate::Sides;

    /// Parameters and height of a mesh vertex, back in the surrogate's frame.
    fn locate(surrogate: &Surrogate, v: &[f64; 3]) -> (f64, f64, f64) {
        surrogate
            .domain
            .locate(&surrogate.frame, DVec3::from_array(*v))
    }

    fn face_normal(mesh: &TriangleMesh, t: &[u32; 3]) -> DVec3 {
        let [a, b, c] = t.map(|i| DVec3::from_array(mesh.vertices[i as usize]));
        (b - a).cross(c - a)
    }

    #[test]
    fn full_trim_counts_match_euler() {
        let surrogate = fitted(Sides::Upper, false);
        let (cs, ct) = (surrogate.trim.cells_s, surrogate.trim.cells_t);
        for n in [1, 2, 5] {
            let mesh = tessellate(&surrogate, Side::Upper, n).unwrap();
            let faces = 4 * n * n * cs * ct;
            assert_eq!(mesh.triangles.len(), faces);
            // A triangulated disk: V = 1 + E - F with E = (3F + B) / 2 and B = 2n (cs + ct)
            // boundary edges, so every shared vertex must be stored exactly once.
            let boundary = 2 * n * (cs + ct);
            assert_eq!(mesh.vertices.len(), 1 + (faces + boundary) / 2, "n = {n}");
        }
    }

    #[test]
    fn every_vertex_lies_on_the_surface() {
        let surrogate = fitted(Sides::Sandwich, true);
        for side in [Side::Upper, Side::Lower] {
            let surface = &surrogate.surface(side).unwrap().surface;
            let mesh = tessellate(&surrogate, side, 3).unwrap();
            assert!(!mesh.triangles.is_empty());
            for v in &mesh.vertices {
                let (s, t, w) = locate(&surrogate, v);
                assert!(surrogate.domain.contains_param(s, t));
                assert!((surface.eval(s, t) - w).abs() < 1e-9, "({s}, {t})");
            }
        }
    }

    #[test]
    fn trimmed_out_triangles_produce_no_faces() {
        let surrogate = fitted(Sides::Upper, true);
        let trim = &surrogate.trim;
        let kept = trim.kept_triangles();
        assert!(
            kept < 4 * trim.cells_s * trim.cells_t && kept > 0,
            "the fixture must trim something"
        );
        let n = 2;
        let mesh = tessellate(&surrogate, Side::Upper, n).unwrap();
        assert_eq!(mesh.triangles.len(), kept * n * n);
        for t in &mesh.triangles {
            let corners = t.map(|i| locate(&surrogate, &mesh.vertices[i as usize]));
            let s = corners.iter().map(|c| c.0).sum::<f64>() / 3.0;
            let t = corners.iter().map(|c| c.1).sum::<f64>() / 3.0;
            let (h, g, u, v) = trim.cell_of(s, t);
            assert_ne!(
                trim.cell_bits(h, g) & triangle_of(u, v),
                0,
                "face at ({s}, {t}) is trimmed out"
            );
        }
    }

    #[test]
    fn normals_face_away_from_the_cloud() {
        let surrogate = fitted(Sides::Sandwich, true);
        let w = surrogate.frame.w;
        for (side, sign) in [(Side::Upper, 1.0), (Side::Lower, -1.0)] {
            let mesh = tessellate(&surrogate, side, 2).unwrap();
            assert!(
                mesh.triangles
                    .iter()
                    .all(|t| sign * face_normal(&mesh, t).dot(w) > 0.0),
                "{side:?}"
            );
        }
    }

    #[test]
    fn absent_sides_are_none_and_all_sides_merge() {
        let upper_only = fitted(Sides::Upper, true);
        assert!(tessellate(&upper_only, Side::Lower, 2).is_none());
        assert_eq!(
            tessellate_all(&upper_only, 2),
            tessellate(&upper_only, Side::Upper, 2).unwrap()
        );
        let sandwich = fitted(Sides::Sandwich, true);
        let (up, low) = (
            tessellate(&sandwich, Side::Upper, 2).unwrap(),
            tessellate(&sandwich, Side::Lower, 2).unwrap(),
        );
        let all = tessellate_all(&sandwich, 2);
        assert_eq!(all.vertices.len(), up.vertices.len() + low.vertices.len());
        assert_eq!(
            all.triangles.len(),
            up.triangles.len() + low.triangles.len()
        );
        assert_eq!(
            tessellate(&sandwich, Side::Upper, 0),
            tessellate(&sandwich, Side::Upper, 1)
        );
    }
}
