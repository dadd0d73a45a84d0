//! An elevation map, the peer a user who needs no smoothness picks (issue 27,
//! `shroud-bench peers`): a grid of per-cell maxima over the cloud's bounding
//! box, as grid_map and elevation_mapping keep for a cloud seen from above.
//! Built by the floor's one pass ([`Floor::cell_maxima`]), so that its build
//! time is the floor's.
//!
//! The query rule, for a sphere of centre `c` and radius `r`: it is
//! *blocked* when its footprint disc (centre `(c.x, c.y)`, radius `r`) leaves
//! the map's box (no data there), or meets a cell that holds no point (no
//! data), or meets a cell whose maximum is at or above the sphere's bottom
//! `c.z - r`; else it is *free*. A cell meets the disc when its rectangle
//! (widened by a hair for the f32 binning) is within `r` of the disc's
//! centre. Every point inside the sphere lies in a cell that meets the disc
//! and is at or above the bottom, so a sphere holding a point is always
//! blocked; the map knows nothing between or under the points (everything
//! below a cell's maximum counts as occupied), and certifies nothing about
//! the space between samples.

use crate::floor::Floor;

/// A `grid x grid` elevation map (see the module docs for its query rule).
#[derive(Debug, Clone)]
pub struct ElevationMap {
    floor: Floor,
}

impl ElevationMap {
    /// An empty map of `grid x grid` cells (`grid >= 1`); every sphere is
    /// blocked until [`Self::build`] gives it points.
    pub fn new(grid: usize) -> Self {
        Self {
            floor: Floor::new(grid),
        }
    }

    /// Cells along a side.
    pub fn grid(&self) -> usize {
        self.floor.grid()
    }

    /// Bins `points` (replacing the previous build): the bounding box of
    /// their `(x, y)` split into `grid x grid` cells, each keeping its
    /// largest `z`.
    pub fn build(&mut self, points: &[[f32; 3]]) {
        self.floor.cell_maxima(points);
    }

    /// Bytes the map needs: one f32 per cell and its box (four f32).
    pub fn storage_bytes(&self) -> usize {
        std::mem::size_of::<f32>() * (self.grid() * self.grid() + 4)
    }

    /// Whether the sphere `(centre, radius)` is blocked (the module's rule).
    pub fn sphere_blocked(&self, centre: [f64; 3], radius: f64) -> bool {
        // A negative or NaN radius is no sphere: never called free.
        if radius.is_nan() || radius < 0.0 || centre.iter().any(|c| !c.is_finite()) {
            return true;
        }
        let [lo, hi] = self.floor.bounds().map(|b| b.map(f64::from));
        let grid = self.grid();
        let width = [0, 1].map(|k| (hi[k] - lo[k]) / grid as f64);
        // The f32 binning may put a point a few ulps across a cell's edge.
        let hair = 1e-5 * (hi[0] - lo[0]).max(hi[1] - lo[1]).max(f64::MIN_POSITIVE);
        let outside = (0..2)
            .any(|k| !(centre[k] - radius >= lo[k] - hair && centre[k] + radius <= hi[k] + hair));
        if outside {
            return true;
        }
        let index = |k: usize, x: f64| {
            let cell = if width[k] > 0.0 {
                ((x - lo[k]) / width[k]).floor()
            } else {
                0.0
            };
            cell.clamp(0.0, (grid - 1) as f64) as usize
        };
        let span =
            |k: usize| index(k, centre[k] - radius - hair)..=index(k, centre[k] + radius + hair);
        let bottom = centre[2] - radius;
        let cells = self.floor.cells();
        span(1).any(|j| {
            span(0).any(|i| {
                // Distance from the disc's centre to the cell's rectangle.
                let gap = |k: usize, n: usize| {
                    let (a, b) = (
                        lo[k] + n as f64 * width[k],
                        lo[k] + (n + 1) as f64 * width[k],
                    );
                    (a - hair - centre[k]).max(centre[k] - b - hair).max(0.0)
                };
                let meets = gap(0, i).hypot(gap(1, j)) <= radius;
                let max = cells[j * grid + i];
                meets && (max == f32::NEG_INFINITY || f64::from(max) >= bottom)
            })
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// A 2 x 2 map over [0, 2]^2 with the cell maxima (0, 0): 1.0, (1, 0):
    /// 0.2, (0, 1): 0.0, (1, 1): 0.5.
    fn two_by_two() -> ElevationMap {
        let mut map = ElevationMap::new(2);
        map.build(&[
            [0.0, 0.0, 1.0],
            [2.0, 2.0, 0.5],
            [1.5, 0.5, 0.2],
            [0.5, 1.5, 0.0],
        ]);
        map
    }

    #[test]
    fn blocked_when_a_cell_under_the_footprint_reaches_the_bottom() {
        let map = two_by_two();
        assert_eq!(map.storage_bytes(), 32);
        // Over cell (1, 0) alone, whose maximum is 0.2.
        assert!(!map.sphere_blocked([1.5, 0.5, 0.45], 0.2));
        // Its bottom at the maximum: blocked (equality counts).
        assert!(map.sphere_blocked([1.5, 0.5, 0.4], 0.2));
        assert!(map.sphere_blocked([1.5, 0.5, 0.45], 0.45));
        // The footprint's square reaches all four cells, the disc misses
        // cell (0, 0) (its corner is 0.3 sqrt 2 > 0.4 away): the tall cell
        // does not count, the highest met cell (0.5) does.
        assert!(!map.sphere_blocked([1.3, 1.3, 1.3], 0.4));
        assert!(map.sphere_blocked([1.3, 1.3, 0.8], 0.4));
        // A disc whose centre is 0.5 from cell (0, 0)'s corner meets the
        // cell with a radius just past that, not just short of it.
        assert!(!map.sphere_blocked([1.3, 1.4, 1.19], 0.49));
        assert!(map.sphere_blocked([1.3, 1.4, 1.21], 0.51));
    }

    #[test]
    fn space_without_data_is_blocked() {
        let map = two_by_two();
        // The footprint leaves the map's box, however high the sphere.
        assert!(map.sphere_blocked([0.1, 1.0, 50.0], 0.2));
        assert!(map.sphere_blocked([1.0, 2.1, 50.0], 0.2));
        // A 3 x 3 map whose middle cell holds no point.
        let mut map = ElevationMap::new(3);
        let ring: Vec<[f32; 3]> = [(0.5, 0.5), (1.5, 0.5), (2.5, 0.5), (0.5, 1.5)]
            .into_iter()
            .chain([(2.5, 1.5), (0.5, 2.5), (1.5, 2.5), (2.5, 2.5)])
            .chain([(0.0, 0.0), (3.0, 3.0)])
            .map(|(x, y)| [x, y, 0.0])
            .collect();
        map.build(&ring);
        assert!(map.sphere_blocked([1.5, 1.5, 9.0], 0.1));
        assert!(!map.sphere_blocked([0.5, 0.5, 9.0], 0.1));
        // Before any build, nothing is known.
        assert!(ElevationMap::new(4).sphere_blocked([0.0, 0.0, 0.0], 1.0));
    }

    #[test]
    fn a_sphere_holding_a_point_is_blocked() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(27);
        for grid in [1, 3, 20, 57] {
            let points: Vec<[f32; 3]> = (0..2000)
                .map(|_| [rng.random(), rng.random::<f32>() * 2.0, rng.random()])
                .collect();
            let mut map = ElevationMap::new(grid);
            map.build(&points);
            for _ in 0..2000 {
                let c = [rng.random::<f64>(), rng.random::<f64>() * 2.0, rng.random()];
                let r = rng.random::<f64>() * 0.2;
                let holds = points.iter().any(|p| {
                    let d = [0, 1, 2].map(|k| f64::from(p[k]) - c[k]);
                    d.iter().map(|x| x * x).sum::<f64>() <= r * r
                });
                assert!(!holds || map.sphere_blocked(c, r), "{grid}: {c:?} {r}");
            }
        }
    }
}
