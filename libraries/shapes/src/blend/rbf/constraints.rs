//! On- and off-surface constraints (Zou et al., Section 5, after Carr et al. 2001):
//! every blending-region point is a zero of `s`; along its normal, at distance `h`
//! on each side, `s` takes the signed distance `+h` (outside) / `-h` (inside). An
//! off-surface point whose nearest surface point is not its own origin would
//! cross the surface, so its `h` is halved (up to three times) or it is dropped.

use glam::DVec3;
use shroud_geometry::cloud::NeighbourIndex;

/// Interpolation data: `values[i]` wanted at `points[i]`; the first `on_surface`
/// entries are the surface points themselves (value 0).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Constraints {
    pub points: Vec<DVec3>,
    pub values: Vec<f64>,
    pub on_surface: usize,
}

/// Builds the constraints from `surface` points with outward unit `normals`
/// (zero normals give no off-surface points) and offset distance `h`.
/// Points closer than `1e-9 h` to an earlier one are dropped (duplicates would
/// make the system singular).
pub fn build_constraints(surface: &[DVec3], normals: &[DVec3], h: f64) -> Constraints {
    let index = NeighbourIndex::new(surface.to_vec());
    let mut keep = vec![true; surface.len()];
    for (i, &p) in surface.iter().enumerate() {
        if keep[i] {
            for (j, _) in index.within(p, 1e-9 * h) {
                if j > i {
                    keep[j] = false;
                }
            }
        }
    }
    let kept: Vec<usize> = (0..surface.len()).filter(|&i| keep[i]).collect();
    let mut out = Constraints {
        points: kept.iter().map(|&i| surface[i]).collect(),
        values: vec![0.0; kept.len()],
        on_surface: kept.len(),
    };
    for &i in &kept {
        let n = normals.get(i).copied().unwrap_or(DVec3::ZERO);
        if n == DVec3::ZERO || !n.is_finite() {
            continue;
        }
        for side in [1.0, -1.0] {
            let mut d = h;
            for _ in 0..4 {
                let q = surface[i] + side * d * n;
                let closest = index
                    .nearest_one(q)
                    .map(|(j, dist)| (j == i) || dist >= d * (1.0 - 1e-9));
                if closest == Some(true) {
                    out.points.push(q);
                    out.values.push(side * d);
                    break;
                }
                d *= 0.5;
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn off_surface_points_do_not_cross() {
        // Two parallel sheets 0.3 apart: h = 1 must shrink to below 0.15 between them.
        let mut pts = Vec::new();
        let mut nrm = Vec::new();
        for i in 0..10 {
            for j in 0..10 {
                let (x, y) = (f64::from(i) * 0.1, f64::from(j) * 0.1);
                pts.push(DVec3::new(x, y, 0.0));
                nrm.push(DVec3::Z);
                pts.push(DVec3::new(x, y, 0.3));
                nrm.push(DVec3::NEG_Z);
            }
        }
        let c = build_constraints(&pts, &nrm, 1.0);
        assert_eq!(c.on_surface, 200);
        for (p, v) in c.points.iter().zip(&c.values).skip(c.on_surface) {
            assert!(v.abs() <= 0.15 || p.z < 0.0 || p.z > 0.3, "{p} {v}");
        }
        let dup = build_constraints(&[DVec3::ZERO, DVec3::ZERO, DVec3::X], &[DVec3::Z; 3], 0.1);
        assert_eq!(dup.on_surface, 2);
    }
}
