//! The guarantee checked from first principles: every input point is evaluated in
//! f64 against each published surface and must lie on the promised side of it;
//! the certificate must report exactly what this check measures.

use super::exact::exact_gap;
use shroud_geometry::spline::{bezier_patch, knot_interval};
use shroud_surrogate::DomainLocate;
use shroud_surrogate::{SafeSurface, Side, Sides, Surrogate};

/// Relative agreement demanded between the certificate and the brute force (the
/// mean is summed in a different order, so it may differ by rounding).
const AGREEMENT: f64 = 1e-9;

/// Gap statistics over all points, `gap = f(s, t) - w` for an upper surface and
/// `w - f(s, t)` for a lower one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gaps {
    pub count: u64,
    pub min: f64,
    pub max: f64,
    pub mean: f64,
    /// The point with the smallest gap: `(index, s, t, w, f)`.
    pub worst: Option<(usize, f64, f64, f64, f64)>,
}

/// Measures the gaps of `points` to one surface of `surrogate`, and checks that
/// every point lies inside the domain and the kept (trimmed) region.
pub fn gaps_of(points: &[[f32; 3]], surrogate: &Surrogate, safe: &SafeSurface) -> Gaps {
    let locator = surrogate.domain.locator(&surrogate.frame);
    let mut gaps = Gaps {
        count: 0,
        min: f64::INFINITY,
        max: f64::NEG_INFINITY,
        mean: 0.0,
        worst: None,
    };
    let mut sum = 0.0;
    for (index, p) in points.iter().enumerate() {
        let (s, t, w) = locator.locate_f32(p);
        assert!(
            surrogate.domain.contains_param(s, t),
            "point {index} {p:?} is outside the domain at ({s}, {t})"
        );
        assert!(
            surrogate.trim.contains(s, t),
            "point {index} {p:?} at ({s}, {t}) lies in a trimmed-away triangle"
        );
        let f = safe.surface.eval(s, t);
        let gap = match safe.side {
            Side::Upper => f - w,
            Side::Lower => w - f,
        };
        if gap < gaps.min {
            gaps.worst = Some((index, s, t, w, f));
        }
        gaps.min = gaps.min.min(gap);
        gaps.max = gaps.max.max(gap);
        sum += gap;
        gaps.count += 1;
    }
    gaps.mean = sum / gaps.count.max(1) as f64;
    gaps
}

/// Whether `a` and `b` agree to [`AGREEMENT`] relative.
pub fn agree(a: f64, b: f64) -> bool {
    (a - b).abs() <= AGREEMENT * a.abs().max(b.abs())
}

/// Panics unless `surrogate` holds exactly the surfaces `sides` asks for, each with
/// every point of `points` on its promised side and a certificate that matches.
pub fn assert_certified(points: &[[f32; 3]], surrogate: &Surrogate, sides: Sides) {
    let expected: &[Side] = match sides {
        Sides::Upper => &[Side::Upper],
        Sides::Lower => &[Side::Lower],
        Sides::Sandwich => &[Side::Upper, Side::Lower],
    };
    let present: Vec<Side> = surrogate.surfaces().map(|s| s.side).collect();
    assert_eq!(present, expected, "surfaces present");
    for &side in expected {
        let safe = surrogate
            .surface(side)
            .unwrap_or_else(|| panic!("no {side:?} surface"));
        assert_certified_surface(points, surrogate, safe, side);
    }
}

fn assert_certified_surface(
    points: &[[f32; 3]],
    surrogate: &Surrogate,
    safe: &SafeSurface,
    side: Side,
) {
    let (domain, surface, cert) = (&surrogate.domain, &safe.surface, &safe.certificate);
    assert_eq!((safe.side, cert.side), (side, side), "side labels");
    assert_eq!(
        (surface.cols, surface.rows),
        (domain.cols, domain.rows),
        "surface and domain sizes"
    );
    assert!(
        surface.coefficients.iter().all(|c| c.is_finite()),
        "non-finite coefficient"
    );
    let gaps = gaps_of(points, surrogate, safe);
    assert!(
        gaps.min >= 0.0,
        "{side:?}: a point is on the wrong side: {gaps:?}"
    );
    assert_eq!(
        cert.points_checked,
        points.len() as u64,
        "{side:?}: points_checked"
    );
    assert_eq!(cert.violations, 0, "{side:?}: violations");
    assert!(
        cert.min_gap >= 0.0,
        "{side:?}: certificate min_gap {}",
        cert.min_gap
    );
    assert!(
        agree(cert.min_gap, gaps.min),
        "{side:?}: min_gap {} vs brute force {}",
        cert.min_gap,
        gaps.min
    );
    assert!(
        agree(cert.max_gap, gaps.max),
        "{side:?}: max_gap {} vs brute force {}",
        cert.max_gap,
        gaps.max
    );
    assert!(
        agree(cert.mean_gap, gaps.mean),
        "{side:?}: mean_gap {} vs brute force {}",
        cert.mean_gap,
        gaps.mean
    );
    let direction = surrogate.frame.direction.to_array();
    assert_eq!(cert.direction, direction, "{side:?}: certificate direction");
}

/// Points on the wrong side of a surface in exact arithmetic (double-double
/// evaluation) or in the Bézier (de Casteljau) evaluation order, described.
/// Certification promises a margin that any evaluation order respects.
pub fn order_independent_violations(points: &[[f32; 3]], surrogate: &Surrogate) -> Vec<String> {
    let locator = surrogate.domain.locator(&surrogate.frame);
    let mut found = Vec::new();
    for safe in surrogate.surfaces() {
        for (index, p) in points.iter().enumerate() {
            let (s, t, w) = locator.locate_f32(p);
            let (gap, error) = exact_gap(&safe.surface, safe.side, s, t, w);
            if gap < -error {
                found.push(format!(
                    "{:?} point {index} {p:?}: exact gap {:e}",
                    safe.side,
                    gap / 36.0
                ));
            }
            let (h, u) = knot_interval(s, safe.surface.cols);
            let (g, v) = knot_interval(t, safe.surface.rows);
            let f = bezier_patch(&safe.surface, h, g).eval(u, v);
            let bezier_gap = if safe.side == Side::Upper {
                f - w
            } else {
                w - f
            };
            if bezier_gap < 0.0 {
                found.push(format!(
                    "{:?} point {index} {p:?}: Bézier-order gap {bezier_gap:e}",
                    safe.side
                ));
            }
        }
    }
    found
}
