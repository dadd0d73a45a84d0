//! Double-double (about 106-bit) evaluation of a surface: decides on which side of
//! the spline a point lies in exact arithmetic, independently of any f64
//! evaluation order. Parameters and heights are taken as the exact f64 values the
//! locator returns.

use shroud_geometry::spline::{knot_interval, UniformCubicSurface};
use shroud_surrogate::Side;

/// An unevaluated sum `hi + lo` with `|lo| <= ulp(hi) / 2`.
#[derive(Debug, Clone, Copy)]
struct Dd {
    hi: f64,
    lo: f64,
}

impl Dd {
    fn new(x: f64) -> Self {
        Self { hi: x, lo: 0.0 }
    }

    /// Knuth's TwoSum then renormalisation: the rounding error is kept, not lost.
    fn add(self, o: Dd) -> Dd {
        let s = self.hi + o.hi;
        let b = s - self.hi;
        let e = (self.hi - (s - b)) + (o.hi - b) + self.lo + o.lo;
        renormalize(s, e)
    }

    /// TwoProduct through a fused multiply-add, which returns the exact error.
    fn mul(self, o: Dd) -> Dd {
        let p = self.hi * o.hi;
        let e = self.hi.mul_add(o.hi, -p) + self.hi * o.lo + self.lo * o.hi;
        renormalize(p, e)
    }

    fn scale(self, k: f64) -> Dd {
        self.mul(Dd::new(k))
    }

    fn value(self) -> f64 {
        self.hi + self.lo
    }
}

fn renormalize(s: f64, e: f64) -> Dd {
    let hi = s + e;
    Dd {
        hi,
        lo: e - (hi - s),
    }
}

/// Six times the four uniform cubic B-spline weights at `u` (integer polynomials,
/// so no division is needed).
fn weights_times_six(u: f64) -> [Dd; 4] {
    let u = Dd::new(u);
    let w = Dd::new(1.0).add(u.scale(-1.0));
    let (u2, w2) = (u.mul(u), w.mul(w));
    let u3 = u2.mul(u);
    [
        w2.mul(w),
        u3.scale(3.0).add(u2.scale(-6.0)).add(Dd::new(4.0)),
        u3.scale(-3.0)
            .add(u2.scale(3.0))
            .add(u.scale(3.0))
            .add(Dd::new(1.0)),
        u3,
    ]
}

/// `36 * gap` at `(s, t)` with `gap = f - w` (upper) or `w - f` (lower), and a
/// bound on its remaining error. The point is on the wrong side in exact
/// arithmetic when the first is below minus the second.
pub fn exact_gap(surface: &UniformCubicSurface, side: Side, s: f64, t: f64, w: f64) -> (f64, f64) {
    let (h, u) = knot_interval(s, surface.cols);
    let (g, v) = knot_interval(t, surface.rows);
    let (a, b) = (weights_times_six(u), weights_times_six(v));
    let c = surface.cell_coefficients(h, g);
    let mut f = Dd::new(0.0);
    let mut magnitude = 0.0;
    for (r, row) in c.iter().enumerate() {
        let mut inner = Dd::new(0.0);
        for (q, &coefficient) in row.iter().enumerate() {
            inner = inner.add(a[q].scale(coefficient));
            magnitude += (b[r].value() * a[q].value() * coefficient).abs();
        }
        f = f.add(b[r].mul(inner));
    }
    let difference = f.add(Dd::new(w).scale(-36.0));
    let gap = match side {
        Side::Upper => difference.value(),
        Side::Lower => -difference.value(),
    };
    (gap, 1e-28 * (magnitude + 36.0 * w.abs()))
}
