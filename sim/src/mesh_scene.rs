//! Triangle meshes of the height scenes, for the range scanner: the table top as a
//! table plane plus closed boxes and cylinders, the terrain as a gridded height
//! field (its cliffs become steep faces one grid cell wide). Pure and
//! deterministic: the same parameters give the same mesh, bit for bit.

use crate::error::{SceneError, MAX_POINTS};
use crate::table_objects::{TableBox, TableCylinder};
use crate::table_top::TableTop;
use crate::terrain::Terrain;
use shroud_shapes::format::TriangleMesh;
use std::f64::consts::TAU;

/// Default number of side segments of a table cylinder's mesh (the polygon is
/// inscribed: its flat sides lie at most `r (1 - cos(pi / 48))`, 0.2 % of the
/// radius, inside the true rim).
pub const DEFAULT_CYLINDER_SEGMENTS: usize = 48;

/// Default terrain mesh resolution: 160 x 120 cells, 0.05 units wide over the
/// default 8 x 6 rectangle (38 400 triangles).
pub const DEFAULT_TERRAIN_CELLS: [usize; 2] = [160, 120];

/// The table plane's mesh is a grid of this many cells along x and y, so
/// that the BVH can bound it tightly (two triangles would overlap every box).
const TABLE_CELLS: usize = 8;

/// Most side segments a cylinder mesh may have.
pub const MAX_CYLINDER_SEGMENTS: usize = 1 << 16;

impl TableTop {
    /// The table as a triangle mesh: the table rectangle at `table_height` (an
    /// 8 x 8 grid of cells, 128 triangles facing up), then each box (8 vertices, 12 triangles) and each
    /// cylinder (a prism of `segments` sides with top and bottom discs), all
    /// closed, standing on the table plane, with outward (counter-clockwise)
    /// triangles. Only the geometry fields are used (not `points`, `noise`,
    /// `wall_fraction` or `seed`). `segments` must lie in `3 ..= 65536`.
    pub fn mesh(&self, segments: usize) -> Result<TriangleMesh, SceneError> {
        self.validate()?;
        check_count("segments", segments, 3, MAX_CYLINDER_SEGMENTS)?;
        let z = self.table_height;
        let [x0, y0] = self.table_min;
        let [x1, y1] = self.table_max;
        let mut mesh = TriangleMesh::default();
        let [nx, ny] = [TABLE_CELLS; 2];
        for j in 0..=ny {
            let y = if j == ny {
                y1
            } else {
                y0 + (y1 - y0) * (j as f64 / ny as f64)
            };
            for i in 0..=nx {
                let x = if i == nx {
                    x1
                } else {
                    x0 + (x1 - x0) * (i as f64 / nx as f64)
                };
                mesh.vertices.push([x, y, z]);
            }
        }
        let at = |i: usize, j: usize| (j * (nx + 1) + i) as u32;
        for j in 0..ny {
            for i in 0..nx {
                let [a, b, c, d] = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
                mesh.triangles.push([a, b, c]);
                mesh.triangles.push([a, c, d]);
            }
        }
        for b in &self.boxes {
            mesh.merge(&box_mesh(b, z));
        }
        for c in &self.cylinders {
            mesh.merge(&cylinder_mesh(c, z, segments));
        }
        Ok(mesh)
    }
}

impl Terrain {
    /// The terrain as a height-field mesh over its rectangle: `(cells[0] + 1) x
    /// (cells[1] + 1)` vertices at the noise-free [`Terrain::height`], two
    /// triangles per cell facing up. A cliff becomes a steep face across the
    /// cells it crosses. Each cell count must be at least 1, and the mesh at most
    /// [`MAX_POINTS`] vertices.
    pub fn mesh(&self, cells: [usize; 2]) -> Result<TriangleMesh, SceneError> {
        self.validate()?;
        let vertices = check_terrain_cells(cells)?;
        let [nx, ny] = cells;
        let mut mesh = TriangleMesh {
            vertices: Vec::with_capacity(vertices),
            triangles: Vec::with_capacity(2 * nx * ny),
        };
        let lerp = |lo: f64, hi: f64, i: usize, n: usize| {
            // Exact at both ends, so the mesh spans the rectangle exactly.
            if i == n {
                hi
            } else {
                lo + (hi - lo) * (i as f64 / n as f64)
            }
        };
        for j in 0..=ny {
            let y = lerp(self.min[1], self.max[1], j, ny);
            for i in 0..=nx {
                let x = lerp(self.min[0], self.max[0], i, nx);
                mesh.vertices.push([x, y, self.height(x, y)]);
            }
        }
        // Below MAX_POINTS (1e8) vertices every index fits in u32.
        let at = |i: usize, j: usize| (j * (nx + 1) + i) as u32;
        for j in 0..ny {
            for i in 0..nx {
                let [a, b, c, d] = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
                mesh.triangles.push([a, b, c]);
                mesh.triangles.push([a, c, d]);
            }
        }
        Ok(mesh)
    }
}

/// Checks terrain mesh cell counts; returns the mesh's vertex count.
pub(crate) fn check_terrain_cells(cells: [usize; 2]) -> Result<usize, SceneError> {
    check_count("cells[0]", cells[0], 1, MAX_POINTS)?;
    check_count("cells[1]", cells[1], 1, MAX_POINTS)?;
    let [nx, ny] = cells;
    (nx + 1)
        .checked_mul(ny + 1)
        .filter(|&v| v <= MAX_POINTS)
        .ok_or(SceneError::TooManyPoints {
            parameter: "cells".into(),
            value: (nx + 1).saturating_mul(ny + 1),
            max: MAX_POINTS,
        })
}

/// Rejects a count outside `[min, max]`.
fn check_count(parameter: &str, value: usize, min: usize, max: usize) -> Result<(), SceneError> {
    if (min..=max).contains(&value) {
        Ok(())
    } else {
        Err(SceneError::OutOfRange {
            parameter: parameter.to_owned(),
            value: value as f64,
            min: min as f64,
            max: max as f64,
        })
    }
}

/// A closed box from the table plane `base` up to `base + height`.
fn box_mesh(b: &TableBox, base: f64) -> TriangleMesh {
    let [x0, y0] = b.min;
    let [x1, y1] = b.max;
    let top = base + b.height;
    let vertices = vec![
        [x0, y0, base],
        [x1, y0, base],
        [x1, y1, base],
        [x0, y1, base],
        [x0, y0, top],
        [x1, y0, top],
        [x1, y1, top],
        [x0, y1, top],
    ];
    // Each face as a quad counter-clockwise seen from outside.
    let quads = [
        [0, 3, 2, 1], // bottom (-z)
        [4, 5, 6, 7], // top (+z)
        [0, 1, 5, 4], // front (-y)
        [1, 2, 6, 5], // right (+x)
        [2, 3, 7, 6], // back (+y)
        [3, 0, 4, 7], // left (-x)
    ];
    TriangleMesh::from_quads(vertices, &quads)
}

/// A closed prism of `segments` sides approximating the cylinder (vertices on the
/// true rim), from the table plane `base` up to `base + height`.
fn cylinder_mesh(c: &TableCylinder, base: f64, segments: usize) -> TriangleMesh {
    let top = base + c.height;
    let n = segments as u32;
    let mut vertices = Vec::with_capacity(2 * segments + 2);
    for k in 0..segments {
        let (sin, cos) = (TAU * k as f64 / segments as f64).sin_cos();
        let [x, y] = [c.centre[0] + c.radius * cos, c.centre[1] + c.radius * sin];
        vertices.push([x, y, base]); // 2k
        vertices.push([x, y, top]); // 2k + 1
    }
    let (bottom_centre, top_centre) = (2 * n, 2 * n + 1);
    vertices.push([c.centre[0], c.centre[1], base]);
    vertices.push([c.centre[0], c.centre[1], top]);
    let mut triangles = Vec::with_capacity(4 * segments);
    for k in 0..n {
        let next = (k + 1) % n;
        let [b0, t0, b1, t1] = [2 * k, 2 * k + 1, 2 * next, 2 * next + 1];
        triangles.push([b0, b1, t1]);
        triangles.push([b0, t1, t0]);
        triangles.push([top_centre, t0, t1]);
        triangles.push([bottom_centre, b1, b0]);
    }
    TriangleMesh {
        vertices,
        triangles,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
        [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
    }

    fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    }

    /// Signed volume by the divergence theorem: positive for a closed mesh with
    /// outward triangles.
    fn volume(mesh: &TriangleMesh) -> f64 {
        mesh.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| mesh.vertices[i as usize]);
                let n = cross(b, c);
                (a[0] * n[0] + a[1] * n[1] + a[2] * n[2]) / 6.0
            })
            .sum()
    }

    /// Every edge of a closed, consistently oriented mesh appears once in each direction.
    fn is_closed(mesh: &TriangleMesh) -> bool {
        let mut edges: Vec<(u32, u32)> = mesh
            .triangles
            .iter()
            .flat_map(|&[a, b, c]| [(a, b), (b, c), (c, a)])
            .collect();
        edges.sort_unstable();
        edges
            .iter()
            .all(|&(a, b)| edges.binary_search(&(b, a)).is_ok())
            && edges.windows(2).all(|w| w[0] != w[1])
    }

    #[test]
    fn boxes_and_cylinders_are_closed_with_the_right_volume() {
        let b = TableBox {
            min: [0.0, 1.0],
            max: [2.0, 4.0],
            height: 0.5,
        };
        let mesh = box_mesh(&b, 1.0);
        assert!(is_closed(&mesh));
        assert!((volume(&mesh) - 3.0).abs() < 1e-12);
        let c = TableCylinder {
            centre: [1.0, -1.0],
            radius: 2.0,
            height: 3.0,
        };
        let n = 64;
        let mesh = cylinder_mesh(&c, -0.5, n);
        assert!(is_closed(&mesh));
        let polygon = 0.5 * n as f64 * 4.0 * (TAU / n as f64).sin();
        assert!((volume(&mesh) - polygon * 3.0).abs() < 1e-9);
    }

    #[test]
    fn table_top_mesh_has_every_object_and_faces_up() {
        let table = TableTop::default();
        let mesh = table.mesh(DEFAULT_CYLINDER_SEGMENTS).unwrap();
        assert_eq!(
            mesh.triangles.len(),
            2 * 64 + 3 * 12 + 4 * DEFAULT_CYLINDER_SEGMENTS
        );
        assert_eq!(mesh.vertices[0], [-4.0, -3.0, 0.0]);
        assert_eq!(mesh.vertices[80], [4.0, 3.0, 0.0]);
        let top = mesh.vertices.iter().map(|v| v[2]).fold(f64::MIN, f64::max);
        assert_eq!(top, 1.4);
        for t in &mesh.triangles[..128] {
            let [a, b, c] = t.map(|i| mesh.vertices[i as usize]);
            assert!(cross(sub(b, a), sub(c, a))[2] > 0.0);
        }
        assert_eq!(mesh, table.mesh(DEFAULT_CYLINDER_SEGMENTS).unwrap());
        let err = table.mesh(2).unwrap_err();
        assert!(err.to_string().contains("segments"), "{err}");
        let bad = TableTop {
            table_height: f64::NAN,
            ..TableTop::default()
        };
        assert!(bad.mesh(8).is_err());
    }

    #[test]
    fn terrain_mesh_samples_the_height_field() {
        let terrain = Terrain::default();
        let mesh = terrain.mesh([16, 12]).unwrap();
        assert_eq!(mesh.vertices.len(), 17 * 13);
        assert_eq!(mesh.triangles.len(), 2 * 16 * 12);
        for &[x, y, z] in &mesh.vertices {
            assert_eq!(z, terrain.height(x, y));
        }
        assert_eq!(mesh.vertices[0][..2], terrain.min);
        assert_eq!(mesh.vertices.last().unwrap()[..2], terrain.max);
        for t in &mesh.triangles {
            let [a, b, c] = t.map(|i| mesh.vertices[i as usize]);
            assert!(cross(sub(b, a), sub(c, a))[2] > 0.0, "triangles face up");
        }
        for cells in [[0, 4], [4, 0], [1 << 40, 1 << 40]] {
            assert!(terrain.mesh(cells).is_err(), "{cells:?}");
        }
    }
}
