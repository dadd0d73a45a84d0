//! The pieces of a ray over the parameter grid: a 2D DDA over the cells its
//! `(s, t)` projection crosses, each crossing split again where it meets the
//! cell's two diagonals. Every piece then lies in one cell (one polynomial) and
//! one trim triangle (Section 6), and pieces come in increasing distance.

use crate::DOMAIN_SLACK;
use std::ops::ControlFlow;

/// A ray in parameter space: `(s, t, w)(λ) = start + λ slope`, `λ` the world distance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParamLine {
    pub start: [f64; 3],
    pub slope: [f64; 3],
}

impl ParamLine {
    #[inline]
    pub fn at(&self, lambda: f64) -> [f64; 3] {
        [0, 1, 2].map(|i| self.start[i] + lambda * self.slope[i])
    }

    /// Whether the projection onto `(s, t)` is a single point.
    pub fn is_vertical(&self) -> bool {
        self.slope[0] == 0.0 && self.slope[1] == 0.0
    }
}

/// The part of the ray inside one cell `(h, g)` and one of its triangles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Piece {
    pub cell: (usize, usize),
    pub lambda: [f64; 2],
}

/// The distances in `range` at which the projection lies in the domain
/// `[0, cells_s] x [0, cells_t]` (with the domain's slack), or `None`.
pub fn clip(line: &ParamLine, cells: (usize, usize), range: [f64; 2]) -> Option<[f64; 2]> {
    let mut r = range;
    for (axis, extent) in [cells.0 as f64, cells.1 as f64].into_iter().enumerate() {
        let (lo, hi) = (-DOMAIN_SLACK, extent + DOMAIN_SLACK);
        let (p, dp) = (line.start[axis], line.slope[axis]);
        if dp == 0.0 {
            if !(lo..=hi).contains(&p) {
                return None;
            }
        } else {
            let (a, b) = ((lo - p) / dp, (hi - p) / dp);
            r = [r[0].max(a.min(b)), r[1].min(a.max(b))];
        }
    }
    (r[0] <= r[1]).then_some(r)
}

/// Visits the pieces of `range` (already clipped) in increasing `λ` until
/// `visit` breaks. A zero-length range yields one zero-length piece.
pub fn walk<B>(
    line: &ParamLine,
    cells: (usize, usize),
    range: [f64; 2],
    mut visit: impl FnMut(Piece) -> ControlFlow<B>,
) -> ControlFlow<B> {
    let [first, last] = range;
    let [s, t, _] = line.at(first);
    let (ds, dt) = (line.slope[0], line.slope[1]);
    let (mut h, mut g) = (start_cell(s, ds, cells.0), start_cell(t, dt, cells.1));
    let mut lambda = first;
    // Each pass ends the walk or steps h or g once: at most cells_s + cells_t passes.
    for _ in 0..=cells.0 + cells.1 {
        let next_s = next_crossing(line.start[0], ds, h, cells.0);
        let next_t = next_crossing(line.start[1], dt, g, cells.1);
        let end = next_s.min(next_t).min(last).max(lambda);
        if end > lambda || first == last {
            split_at_diagonals(line, (h, g), [lambda, end], &mut visit)?;
        }
        if end >= last {
            break;
        }
        if next_s <= end {
            h = if ds > 0.0 { h + 1 } else { h - 1 };
        }
        if next_t <= end {
            g = if dt > 0.0 { g + 1 } else { g - 1 };
        }
        lambda = end;
    }
    ControlFlow::Continue(())
}

/// The cell the ray is in just after parameter `p`: on a knot, the one it moves into.
#[inline]
fn start_cell(p: f64, dp: f64, cells: usize) -> usize {
    let p = p.clamp(0.0, cells as f64);
    let index = if dp < 0.0 { p.ceil() - 1.0 } else { p.floor() };
    (index.max(0.0) as usize).min(cells - 1)
}

/// Distance at which the ray leaves cell `index` along one axis; infinite when it
/// does not, or when that cell is the last one in its direction (the clip ends it).
#[inline]
fn next_crossing(p0: f64, dp: f64, index: usize, cells: usize) -> f64 {
    if dp > 0.0 && index + 1 < cells {
        ((index + 1) as f64 - p0) / dp
    } else if dp < 0.0 && index > 0 {
        (index as f64 - p0) / dp
    } else {
        f64::INFINITY
    }
}

/// Splits a cell crossing at the diagonals `u = v` and `u + v = 1`.
fn split_at_diagonals<B>(
    line: &ParamLine,
    cell: (usize, usize),
    [a, b]: [f64; 2],
    visit: &mut impl FnMut(Piece) -> ControlFlow<B>,
) -> ControlFlow<B> {
    let (su, tv) = (line.start[0] - cell.0 as f64, line.start[1] - cell.1 as f64);
    let (ds, dt) = (line.slope[0], line.slope[1]);
    let main = -(su - tv) / (ds - dt);
    let anti = -(su + tv - 1.0) / (ds + dt);
    let inside = |x: f64| x > a && x < b; // false for NaN and infinities
    let mut cuts = [a, a];
    let mut n = 0;
    for x in [main, anti] {
        if inside(x) {
            cuts[n] = x;
            n += 1;
        }
    }
    if n == 2 && cuts[1] < cuts[0] {
        cuts.swap(0, 1);
    }
    if n == 2 && cuts[0] == cuts[1] {
        n = 1; // through the cell centre, where the diagonals meet
    }
    let mut from = a;
    for &cut in &cuts[..n] {
        visit(Piece {
            cell,
            lambda: [from, cut],
        })?;
        from = cut;
    }
    visit(Piece {
        cell,
        lambda: [from, b],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::trim::triangle_of;

    fn pieces(line: ParamLine, cells: (usize, usize), range: [f64; 2]) -> Vec<Piece> {
        let mut out = Vec::new();
        let clipped = clip(&line, cells, range).unwrap();
        let _ = walk::<()>(&line, cells, clipped, |p| {
            out.push(p);
            ControlFlow::Continue(())
        });
        out
    }

    /// Pieces are contiguous, each inside its cell and one triangle.
    fn check_partition(line: ParamLine, cells: (usize, usize), range: [f64; 2]) -> Vec<Piece> {
        let ps = pieces(line, cells, range);
        let clipped = clip(&line, cells, range).unwrap();
        assert_eq!(ps[0].lambda[0], clipped[0]);
        assert_eq!(ps[ps.len() - 1].lambda[1], clipped[1]);
        for w in ps.windows(2) {
            assert_eq!(w[0].lambda[1], w[1].lambda[0]);
        }
        for p in &ps {
            assert!(p.lambda[0] <= p.lambda[1]);
            let [s, t, _] = line.at(0.5 * (p.lambda[0] + p.lambda[1]));
            let (u, v) = (s - p.cell.0 as f64, t - p.cell.1 as f64);
            assert!(
                (-1e-9..=1.0 + 1e-9).contains(&u) && (-1e-9..=1.0 + 1e-9).contains(&v),
                "{p:?}"
            );
            for end in p.lambda {
                let [se, te, _] = line.at(end);
                let (ue, ve) = (se - p.cell.0 as f64, te - p.cell.1 as f64);
                // Both ends see the midpoint's triangle or lie on its boundary.
                let mid = triangle_of(u, v);
                let near = [
                    (0.0, 0.0),
                    (1e-9, 0.0),
                    (-1e-9, 0.0),
                    (0.0, 1e-9),
                    (0.0, -1e-9),
                ]
                .iter()
                .any(|(a, b)| triangle_of(ue + a, ve + b) == mid);
                assert!(near || p.lambda[0] == p.lambda[1], "{p:?} end {end}");
            }
        }
        ps
    }

    #[test]
    fn diagonal_ray_crosses_cells_and_triangles_in_order() {
        let line = ParamLine {
            start: [-1.0, -0.5, 0.0],
            slope: [0.8, 0.6, 0.0],
        };
        let ps = check_partition(line, (4, 3), [0.0, 100.0]);
        assert!(ps.len() > 8);
        let cells: Vec<_> = ps.iter().map(|p| p.cell).collect();
        assert!(cells
            .windows(2)
            .all(|w| w[1].0 >= w[0].0 && w[1].1 >= w[0].1));
    }

    #[test]
    fn backward_and_axis_parallel_rays() {
        check_partition(
            ParamLine {
                start: [3.7, 2.9, 0.0],
                slope: [-0.3, -0.9, 0.0],
            },
            (4, 3),
            [0.0, 50.0],
        );
        let along_edge = check_partition(
            ParamLine {
                start: [0.0, 1.0, 0.0],
                slope: [1.0, 0.0, 0.0],
            },
            (4, 3),
            [0.0, 3.5],
        );
        assert_eq!(
            along_edge.len(),
            4,
            "an edge meets the diagonals only at cell corners"
        );
        let through_centres = check_partition(
            ParamLine {
                start: [0.0, 1.5, 0.0],
                slope: [1.0, 0.0, 0.0],
            },
            (4, 3),
            [0.0, 9.0],
        );
        assert_eq!(
            through_centres.len(),
            8,
            "each cell splits once, at its centre"
        );
        check_partition(
            ParamLine {
                start: [2.0, 0.0, 0.0],
                slope: [1.0, 1.0, 0.0],
            },
            (4, 3),
            [0.0, 9.0],
        );
    }

    #[test]
    fn vertical_and_zero_length_rays_give_one_piece() {
        let vertical = ParamLine {
            start: [1.5, 2.5, 0.0],
            slope: [0.0, 0.0, 1.0],
        };
        assert!(vertical.is_vertical());
        assert_eq!(
            pieces(vertical, (4, 3), [0.0, 5.0]),
            vec![Piece {
                cell: (1, 2),
                lambda: [0.0, 5.0]
            }]
        );
        let corner = ParamLine {
            start: [4.0, 3.0, 0.0],
            slope: [1.0, 0.0, 0.0],
        };
        let ps = pieces(corner, (4, 3), [0.0, 1.0]);
        assert_eq!(ps.len(), 1);
        assert_eq!(ps[0].cell, (3, 2));
        assert!(
            ps[0].lambda[1] <= 2.0 * DOMAIN_SLACK,
            "leaves the domain within its slack"
        );
        let point = ParamLine {
            start: [1.5, 0.5, 0.0],
            slope: [1.0, 0.0, 0.0],
        };
        assert_eq!(
            pieces(point, (4, 3), [0.0, 0.0]),
            vec![Piece {
                cell: (1, 0),
                lambda: [0.0, 0.0]
            }]
        );
    }

    #[test]
    fn rays_missing_the_domain_are_clipped_away() {
        let beside = ParamLine {
            start: [-1.0, 5.0, 0.0],
            slope: [1.0, 0.0, 0.0],
        };
        assert_eq!(clip(&beside, (4, 3), [0.0, 10.0]), None);
        let away = ParamLine {
            start: [-1.0, 1.0, 0.0],
            slope: [-1.0, 0.0, 0.0],
        };
        assert_eq!(clip(&away, (4, 3), [0.0, 10.0]), None);
        let short = ParamLine {
            start: [-1.0, 1.0, 0.0],
            slope: [1.0, 0.0, 0.0],
        };
        assert_eq!(clip(&short, (4, 3), [0.0, 0.5]), None);
    }
}
