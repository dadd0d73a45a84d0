//! A scan's rays that came back empty, as the few cones a cloud carries
//! ([`NoReturn`]), for a sensor whose rays lie on a grid of rows and columns.
//!
//! Which empty rays count: those of an 8-connected group of empty rays that
//! holds a full 2 x 2 block. On a square grid of equal spacings, an object
//! whose image covers a disc of radius `sqrt(2)` ray spacings covers such a
//! block wherever it falls, so every object larger than that is kept (rows
//! of a point budget that differ by a ray are shifted by up to a column,
//! and unequal spacings count by the larger); what is dropped are lone
//! dropouts and thin lines of them (a random 1 % dropout rate makes a 2 x 2
//! block about once in 10^8 positions), which are below the resolution at
//! which the scan can promise anything anyway, like objects between rays.
//!
//! Each kept ray stands for the space up to its neighbours (an object that
//! touches it may fill the gap to the next ray that returned), so its cone is
//! its direction widened by `spread`, the largest angle between a ray and a
//! neighbour. Rays are merged in square tiles, as small as
//! [`MAX_DARK_CONES`] allows: a tile's cone is centred on the mean of its
//! rays' directions and reaches the farthest of them plus `spread`.

use glam::DVec3;
use shroud_msg::{DarkCone, MessageError, NoReturn, MAX_DARK_CONES};
use std::collections::BTreeMap;

/// Added to every half angle: the directions a producer computes in f32.
const ROUNDING: f64 = 1e-6;

/// A scan's grid of rays: `rows x columns`, row-major; `empty[i]` when ray
/// `i` was cast and returned nothing within range (rays not cast, outside a
/// round aperture, are `false`).
#[derive(Debug, Clone, Copy)]
pub struct EmptyRays<'a> {
    pub rows: usize,
    pub columns: usize,
    pub empty: &'a [bool],
}

impl EmptyRays<'_> {
    fn at(&self, row: isize, column: isize) -> bool {
        row >= 0
            && column >= 0
            && (row as usize) < self.rows
            && (column as usize) < self.columns
            && self.empty[row as usize * self.columns + column as usize]
    }

    /// Whether ray `(r, c)` is the top-left corner of a 2 x 2 block of
    /// empty rays.
    fn starts_block(&self, r: isize, c: isize) -> bool {
        self.at(r, c) && self.at(r + 1, c) && self.at(r, c + 1) && self.at(r + 1, c + 1)
    }

    /// The empty rays that belong to a group holding a 2 x 2 block, as
    /// indices into the grid (`empty` holds `rows * columns` flags).
    fn kept(&self) -> Vec<usize> {
        let n = self.rows * self.columns;
        let mut group = vec![usize::MAX; n];
        let mut kept = Vec::new();
        let mut stack = Vec::new();
        let mut members = Vec::new();
        for start in 0..n {
            if !self.empty[start] || group[start] != usize::MAX {
                continue;
            }
            group[start] = start;
            stack.push(start);
            members.clear();
            let mut has_block = false;
            while let Some(i) = stack.pop() {
                members.push(i);
                let (r, c) = ((i / self.columns) as isize, (i % self.columns) as isize);
                for (dr, dc) in NEIGHBOURS {
                    let (nr, nc) = (r + dr, c + dc);
                    if !self.at(nr, nc) {
                        continue;
                    }
                    let j = nr as usize * self.columns + nc as usize;
                    if group[j] == usize::MAX {
                        group[j] = start;
                        stack.push(j);
                    }
                }
                has_block |= self.starts_block(r, c);
            }
            if has_block {
                kept.extend_from_slice(&members);
            }
        }
        kept.sort_unstable();
        kept
    }
}

const NEIGHBOURS: [(isize, isize); 8] = [
    (-1, -1),
    (-1, 0),
    (-1, 1),
    (0, -1),
    (0, 1),
    (1, -1),
    (1, 0),
    (1, 1),
];

/// The angle between two unit vectors, accurate for small angles too.
fn angle(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b))
}

/// The cones of `rays`' kept empty rays, seen from `apex`: `direction(i)` is
/// ray `i`'s unit direction, `spread` the largest angle between a ray and a
/// neighbour (radians). `Ok(None)` when no empty ray is kept; an error when
/// `empty` is not `rows * columns` flags, or a tile would need a cone of 90
/// degrees or more (a grid too coarse for [`MAX_DARK_CONES`] tiles, a field
/// of view near a half space).
pub fn dark_cones(
    apex: [f64; 3],
    rays: &EmptyRays<'_>,
    direction: impl Fn(usize) -> DVec3,
    spread: f64,
) -> Result<Option<NoReturn>, MessageError> {
    if Some(rays.empty.len()) != rays.rows.checked_mul(rays.columns) {
        return Err(MessageError::Invalid {
            field: "no_return",
            reason: format!(
                "{} ray flags for a grid of {} x {}",
                rays.empty.len(),
                rays.rows,
                rays.columns
            ),
        });
    }
    let kept = rays.kept();
    if kept.is_empty() {
        return Ok(None);
    }
    let directions: Vec<(usize, DVec3)> = kept.iter().map(|&i| (i, direction(i))).collect();
    let mut side = 1;
    loop {
        let mut tiles: BTreeMap<(usize, usize), Vec<DVec3>> = BTreeMap::new();
        for &(i, d) in &directions {
            let (r, c) = (i / rays.columns, i % rays.columns);
            tiles.entry((r / side, c / side)).or_default().push(d);
        }
        if tiles.len() > MAX_DARK_CONES {
            side *= 2;
            continue;
        }
        let cones = tiles
            .values()
            .map(|members| cone_around(members, spread))
            .collect();
        let no_return = NoReturn { apex, cones };
        no_return.validate()?;
        return Ok(Some(no_return));
    }
}

/// The cone around the mean of `members` that holds each of them widened by
/// `spread`.
fn cone_around(members: &[DVec3], spread: f64) -> DarkCone {
    let sum: DVec3 = members.iter().copied().sum();
    let axis = sum.normalize_or(members[0]);
    let reach = members.iter().map(|&d| angle(axis, d)).fold(0.0, f64::max);
    DarkCone {
        axis: axis.to_array(),
        half_angle: reach + spread + ROUNDING,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(rows: usize, columns: usize, empty: &[(usize, usize)]) -> Vec<bool> {
        let mut g = vec![false; rows * columns];
        for &(r, c) in empty {
            g[r * columns + c] = true;
        }
        g
    }

    #[test]
    fn only_groups_holding_a_block_are_kept() {
        // A lone dropout, a diagonal line of three, and a 2 x 2 block with a
        // ray above it and one diagonally below.
        let empty = grid(
            8,
            8,
            &[
                (0, 7),
                (2, 0),
                (3, 1),
                (4, 2),
                (5, 5),
                (5, 6),
                (6, 5),
                (6, 6),
                (7, 7),
                (4, 6),
            ],
        );
        let rays = EmptyRays {
            rows: 8,
            columns: 8,
            empty: &empty,
        };
        let kept = rays.kept();
        assert_eq!(
            kept,
            vec![4 * 8 + 6, 5 * 8 + 5, 5 * 8 + 6, 6 * 8 + 5, 6 * 8 + 6, 63]
        );
    }

    /// A pinhole grid: ray `(r, c)` through `(c - 20, r - 15) * step` on the
    /// image plane at unit distance below the apex.
    fn pinhole(i: usize, columns: usize, step: f64) -> DVec3 {
        let (r, c) = ((i / columns) as f64, (i % columns) as f64);
        DVec3::new((c - 20.0) * step, (r - 15.0) * step, -1.0).normalize()
    }

    #[test]
    fn every_kept_ray_and_its_neighbourhood_lies_in_a_cone() {
        let (rows, columns, step) = (30, 40, 0.01);
        let mut empty = vec![false; rows * columns];
        // A blob of empty rays and a wide empty band.
        for r in 5..12 {
            for c in 8..13 {
                empty[r * columns + c] = true;
            }
        }
        for c in 0..columns {
            empty[25 * columns + c] = true;
            empty[26 * columns + c] = true;
        }
        let rays = EmptyRays {
            rows,
            columns,
            empty: &empty,
        };
        let spread = (2.0f64).sqrt() * step;
        let nr = dark_cones(
            [0.0, 0.0, 1.0],
            &rays,
            |i| pinhole(i, columns, step),
            spread,
        )
        .unwrap()
        .unwrap();
        assert_eq!(nr.cones.len(), rays.kept().len(), "one cone a ray when few");
        let inside = |d: DVec3| {
            nr.cones
                .iter()
                .any(|c| angle(DVec3::from_array(c.axis), d) <= c.half_angle)
        };
        for i in rays.kept() {
            let d = pinhole(i, columns, step);
            assert!(inside(d));
            // Up to a diagonal neighbour is covered too, every way.
            let (r, c) = ((i / columns) as f64, (i % columns) as f64);
            for (dr, dc) in [(1.0, 1.0), (-1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)] {
                let n = DVec3::new((c + dc - 20.0) * step, (r + dr - 15.0) * step, -1.0);
                assert!(inside(n.normalize()));
            }
        }
        // A ray far from both is not.
        assert!(!inside(pinhole(18 * columns + 30, columns, step)));
    }

    #[test]
    fn many_empty_rays_merge_into_at_most_the_cap() {
        let (rows, columns, step) = (300, 400, 0.002);
        let empty = vec![true; rows * columns];
        let rays = EmptyRays {
            rows,
            columns,
            empty: &empty,
        };
        let direction = |i: usize| {
            let (r, c) = ((i / columns) as f64, (i % columns) as f64);
            DVec3::new((c - 200.0) * step, (r - 150.0) * step, -1.0).normalize()
        };
        let nr = dark_cones([0.0; 3], &rays, direction, 0.003)
            .unwrap()
            .unwrap();
        assert!(nr.cones.len() <= MAX_DARK_CONES && nr.cones.len() > MAX_DARK_CONES / 4);
        for i in (0..rows * columns).step_by(97) {
            // A ray, and a direction `spread` off it, each in some cone.
            let d = direction(i);
            let off = (d + d.any_orthonormal_vector() * 0.003f64.tan()).normalize();
            for probe in [d, off] {
                assert!(nr
                    .cones
                    .iter()
                    .any(|c| angle(DVec3::from_array(c.axis), probe) <= c.half_angle));
            }
        }
        let short = EmptyRays {
            rows,
            columns,
            empty: &empty[1..],
        };
        assert!(dark_cones([0.0; 3], &short, direction, 0.003).is_err());
        let none = vec![false; rows * columns];
        let rays = EmptyRays {
            rows,
            columns,
            empty: &none,
        };
        assert_eq!(dark_cones([0.0; 3], &rays, direction, 0.003).unwrap(), None);
    }
}
