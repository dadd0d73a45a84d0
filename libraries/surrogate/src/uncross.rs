//! Sandwich surfaces never cross: on every kept cell the difference `upper - lower`
//! is a spline whose coefficients are the coefficient differences, so making those
//! non-negative makes the difference non-negative (convex hull property). Moving
//! the upper surface up and the lower one down keeps both safe.

use super::trim::TrimMask;
use shroud_geometry::spline::UniformCubicSurface;

/// Adjusts coefficients acting on kept cells; returns how many pairs moved.
pub fn uncross(
    upper: &mut UniformCubicSurface,
    lower: &mut UniformCubicSurface,
    trim: &TrimMask,
) -> u64 {
    let (cs, ct) = upper.cells();
    let mut moved = 0;
    for k in 0..upper.rows {
        for j in 0..upper.cols {
            let touches_kept = (k.saturating_sub(2)..=(k + 1).min(ct - 1))
                .any(|g| (j.saturating_sub(2)..=(j + 1).min(cs - 1)).any(|h| trim.cell_kept(h, g)));
            let i = k * upper.cols + j;
            let d = upper.coefficients[i] - lower.coefficients[i];
            if touches_kept && d < 0.0 {
                // Meet in the middle: `mid` lies in [upper, lower], so upper only
                // rises, lower only falls, and the difference becomes exactly 0.
                let (up, low) = (upper.coefficients[i], lower.coefficients[i]);
                let mid = up + (low - up) * 0.5;
                upper.coefficients[i] = mid;
                lower.coefficients[i] = mid;
                moved += 1;
            }
        }
    }
    moved
}
