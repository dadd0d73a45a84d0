//! The tightness measure: the volume between a safe surface and the data's
//! envelope over the kept region. Methods are compared by the ratio of their
//! excess volume to that of the LP optimum ([`super::lp_reference`]).
//!
//! Definition (one choice, used everywhere):
//! * each grid cell is split into `raster x raster` squares and each square by its
//!   two diagonals into four *pieces*; the cell's own diagonals run along piece
//!   edges, so every piece lies in exactly one trim triangle (Section 6);
//! * the envelope of a piece is the largest signed height (`side.sign() * w`) of
//!   the points in it;
//! * a piece of a kept triangle without points takes the lowest data level within
//!   the reach of its cell: the lowest candidate (sub-cell extreme, as the fitter
//!   picks them) of the kept cells that share a coefficient with it (the least
//!   [`super::bounds::floors_of`] of its 16 coefficients). A surface
//!   may dip below that level between points (the LP's only floor lies far below
//!   the data, see [`super::bounds::safety_floor`]); such dips count negative;
//! * the surface is integrated exactly over each kept piece, so the excess is
//!   `∫_kept sign f - ∫_kept envelope`: the LP objective minus a constant, and the
//!   LP optimum has the least excess of all safe surfaces within its bounds.
//!
//! Reported in world units (parameter area times `u_step * v_step`).

use super::bounds::floors_of;
use super::cells::cell_slots;
use super::cloud_side::CloudSide;
use super::lp::group_by_cell;
use super::lp_reference::candidate_indices;
use super::quadrature::{corners, triangle_moments, Moments, TRIANGLES};
use crate::trim::triangle_of;
use crate::{Candidate, FitOptions, Side, TrimMask};
use shroud_geometry::spline::{knot_interval, UniformCubicSurface};

/// Raster squares per cell along each parameter.
pub const DEFAULT_RASTER: usize = 8;

/// The envelope of one side of a cloud on the piece raster.
#[derive(Debug, Clone)]
pub struct Envelope {
    raster: usize,
    trim: TrimMask,
    side: Side,
    /// World area of one parameter unit.
    area_scale: f64,
    /// Signed envelope per piece (see [`Envelope::slot`]), filled in for empty
    /// kept pieces; `NaN` for pieces of trimmed triangles.
    level: Vec<f64>,
    /// Exact moments of each piece of a cell, `[(l * raster + i) * 4 + piece]`.
    moments: Vec<Moments>,
    /// Trim bit of the cell triangle holding each piece, same order.
    owner: Vec<u8>,
}

impl Envelope {
    /// `sub_cells`: the candidate sub-cells per cell the empty pieces' levels
    /// come from (the fitter's `FitOptions::sub_cells`).
    pub fn new(cloud: &CloudSide, raster: usize, sub_cells: usize) -> Self {
        let raster = raster.max(1);
        let trim = cloud.trim.clone();
        let per_cell = raster * raster * 4;
        let mut envelope = Self {
            raster,
            side: cloud.side,
            area_scale: cloud.domain.u_step * cloud.domain.v_step,
            level: vec![f64::NEG_INFINITY; trim.cells_s * trim.cells_t * per_cell],
            moments: Vec::with_capacity(per_cell),
            owner: Vec::with_capacity(per_cell),
            trim,
        };
        envelope.tabulate_pieces();
        for c in cloud.constraints() {
            let slot = envelope.slot_of(c.s, c.t);
            envelope.level[slot] = envelope.level[slot].max(c.height);
        }
        envelope.fill_empty_pieces(&empty_levels(cloud, sub_cells));
        envelope
    }

    fn tabulate_pieces(&mut self) {
        let size = 1.0 / self.raster as f64;
        for l in 0..self.raster {
            for i in 0..self.raster {
                for t in TRIANGLES {
                    let c = corners(t, i as f64 * size, l as f64 * size, size);
                    let centroid = [
                        (c[0][0] + c[1][0] + c[2][0]) / 3.0,
                        (c[0][1] + c[1][1] + c[2][1]) / 3.0,
                    ];
                    self.moments.push(triangle_moments(c));
                    self.owner.push(triangle_of(centroid[0], centroid[1]));
                }
            }
        }
    }

    /// Piece holding parameters `(s, t)`.
    fn slot_of(&self, s: f64, t: f64) -> usize {
        let r = self.raster as f64;
        let (h, u) = knot_interval(s, self.trim.cells_s + 1);
        let (g, v) = knot_interval(t, self.trim.cells_t + 1);
        let (i, l) = (
            ((u * r) as usize).min(self.raster - 1),
            ((v * r) as usize).min(self.raster - 1),
        );
        let piece = TRIANGLES
            .iter()
            .position(|&b| b == triangle_of(u * r - i as f64, v * r - l as f64))
            .unwrap_or(0);
        self.slot(h, g) + (l * self.raster + i) * 4 + piece
    }

    /// First piece of cell `(h, g)`.
    fn slot(&self, h: usize, g: usize) -> usize {
        (g * self.trim.cells_s + h) * self.raster * self.raster * 4
    }

    /// Marks pieces of trimmed triangles and fills empty kept ones.
    fn fill_empty_pieces(&mut self, empty_level: &[f64]) {
        let per_cell = self.raster * self.raster * 4;
        for g in 0..self.trim.cells_t {
            for h in 0..self.trim.cells_s {
                let fill = empty_level[g * self.trim.cells_s + h];
                let (first, bits) = (self.slot(h, g), self.trim.cell_bits(h, g));
                for (k, value) in self.level[first..first + per_cell].iter_mut().enumerate() {
                    *value =
                        if bits & self.owner[k] == 0 || !(value.is_finite() || fill.is_finite()) {
                            f64::NAN
                        } else if value.is_finite() {
                            *value
                        } else {
                            fill
                        };
                }
            }
        }
    }

    /// Excess volume of `surface` (real heights, on this envelope's side) in
    /// world units.
    pub fn excess(&self, surface: &UniformCubicSurface) -> f64 {
        let sign = self.side.sign();
        let per_cell = self.raster * self.raster * 4;
        let mut total = 0.0;
        for g in 0..self.trim.cells_t {
            for h in 0..self.trim.cells_s {
                if !self.trim.cell_kept(h, g) {
                    continue;
                }
                let c = surface.cell_coefficients(h, g);
                let first = self.slot(h, g);
                for (k, m) in self.moments.iter().enumerate().take(per_cell) {
                    let level = self.level[first + k];
                    if level.is_nan() {
                        continue;
                    }
                    let mut integral = 0.0;
                    let mut area = 0.0;
                    for r in 0..4 {
                        for q in 0..4 {
                            integral += m[r][q] * c[r][q];
                            area += m[r][q];
                        }
                    }
                    total += sign * integral - level * area;
                }
            }
        }
        total * self.area_scale
    }
}

/// Excess volume of `surface` over `cloud` on the default raster with the
/// default candidate sub-cells (see the module documentation for the definition).
pub fn excess_volume(cloud: &CloudSide, surface: &UniformCubicSurface) -> f64 {
    Envelope::new(cloud, DEFAULT_RASTER, FitOptions::default().sub_cells).excess(surface)
}

/// The level of each cell's empty pieces: the lowest candidate of the kept
/// cells sharing a coefficient with it (`+inf` where there is none).
fn empty_levels(cloud: &CloudSide, sub_cells: usize) -> Vec<f64> {
    let (cols, rows) = (cloud.trim.cells_s + 1, cloud.trim.cells_t + 1);
    let all: Vec<Candidate> = cloud.constraints().collect();
    let candidates: Vec<Candidate> = candidate_indices(cloud, sub_cells)
        .iter()
        .map(|&i| all[i as usize])
        .collect();
    let lowest = floors_of(
        cols,
        rows,
        &group_by_cell(cols, rows, &candidates),
        cloud.trim,
    );
    (0..(cols - 1) * (rows - 1))
        .map(|cell| {
            let (h, g) = (cell % (cols - 1), cell / (cols - 1));
            cell_slots(h, g, cols, rows)
                .iter()
                .fold(f64::INFINITY, |m, &i| m.min(lowest[i]))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Domain;
    use glam::DVec3;
    use shroud_geometry::math::Frame;

    fn flat_cloud() -> Vec<[f32; 3]> {
        (0..4000)
            .map(|i| [(i % 80) as f32 * 0.05, (i / 80) as f32 * 0.06, 0.25])
            .collect()
    }

    #[test]
    fn a_constant_surface_above_a_flat_cloud_has_height_times_area() {
        let frame = Frame::from_direction(DVec3::new(0.0, 0.0, -1.0)).unwrap();
        let domain = Domain {
            u_min: 0.0,
            v_min: 0.0,
            u_step: 1.0,
            v_step: 1.5,
            cols: 5,
            rows: 3,
        };
        let trim = TrimMask::full(4, 2);
        let pts = flat_cloud();
        let cloud = CloudSide {
            points: &pts,
            frame: &frame,
            domain: &domain,
            trim: &trim,
            side: Side::Upper,
        };
        let surface = UniformCubicSurface::constant(5, 3, 1.0).unwrap();
        // The parameter domain is 4 x 2 (area 8), 12 in world units; gap 0.75.
        let excess = excess_volume(&cloud, &surface);
        assert!((excess - 0.75 * 12.0).abs() < 1e-9, "{excess}");
    }

    #[test]
    fn trimmed_triangles_and_the_lower_side_are_measured_consistently() {
        let frame = Frame::from_direction(DVec3::new(0.0, 0.0, -1.0)).unwrap();
        let domain = Domain {
            u_min: 0.0,
            v_min: 0.0,
            u_step: 1.0,
            v_step: 1.0,
            cols: 5,
            rows: 3,
        };
        let mut trim = TrimMask::full(4, 2);
        trim.bits
            .iter_mut()
            .enumerate()
            .for_each(|(i, b)| *b = (i as u8 * 5) & 0b1111);
        let kept = trim.kept_area();
        let pts = flat_cloud();
        let low = UniformCubicSurface::constant(5, 3, -0.5).unwrap();
        let cloud = CloudSide {
            points: &pts,
            frame: &frame,
            domain: &domain,
            trim: &trim,
            side: Side::Lower,
        };
        let excess = excess_volume(&cloud, &low);
        assert!(
            (excess - 0.75 * kept).abs() < 1e-9,
            "{excess} vs {}",
            0.75 * kept
        );
    }

    #[test]
    fn the_excess_is_the_kept_integral_minus_a_constant() {
        // Raising one coefficient by d raises the excess by d * c_jk * area scale.
        let frame = Frame::from_direction(DVec3::new(0.0, 0.0, -1.0)).unwrap();
        let domain = Domain {
            u_min: 0.0,
            v_min: 0.0,
            u_step: 0.5,
            v_step: 2.0,
            cols: 5,
            rows: 4,
        };
        let mut trim = TrimMask::full(4, 3);
        trim.bits
            .iter_mut()
            .enumerate()
            .for_each(|(i, b)| *b = (i as u8 * 7 + 3) & 0b1111);
        let pts: Vec<[f32; 3]> = (0..5000)
            .map(|i| {
                [
                    (i % 100) as f32 * 0.02,
                    (i / 100) as f32 * 0.12,
                    ((i * 31) % 17) as f32 * 0.1,
                ]
            })
            .collect();
        let cloud = CloudSide {
            points: &pts,
            frame: &frame,
            domain: &domain,
            trim: &trim,
            side: Side::Upper,
        };
        let envelope = Envelope::new(&cloud, 4, 2);
        let mut surface = UniformCubicSurface::constant(5, 4, 3.0).unwrap();
        let weights = super::super::objective_weights(5, 4, &trim);
        let base = envelope.excess(&surface);
        surface.coefficients[7] += 0.5;
        let raised = envelope.excess(&surface);
        assert!(
            (raised - base - 0.5 * weights[7] * 1.0).abs() < 1e-12,
            "{} vs {}",
            raised - base,
            0.5 * weights[7]
        );
    }
}
