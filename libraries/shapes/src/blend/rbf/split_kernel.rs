//! The cubic kernel `r^3` split at a radius `R` into a smooth far part and a
//! compactly supported near part, `r^3 = far(r) + near(r)` (the splitting of
//! multilevel summation: Skeel, Tezcan and Hardy, "Multiple grid methods for
//! classical molecular dynamics", 2002). Beyond `R` the far part is `r^3` itself
//! and the near part vanishes; within `R` the far part is the even polynomial
//! `R^3 G((r/R)^2)` that meets `r^3` at `R` with six matching derivatives, so
//! a sum of far parts is smooth everywhere (C^6) and interpolates well from a
//! coarse lattice (to sixth order), while a near sum only needs the centres
//! within `R`.

/// `G(t) = sum_k b_k t^k`: `G(1) = 1` and, in `rho = sqrt(t)`, the first to
/// sixth derivatives at `rho = 1` equal those of `rho^3` (3, 6, 6, 0, 0, 0).
const SMOOTHING: [f64; 7] = [
    -21.0 / 1024.0,
    189.0 / 512.0,
    945.0 / 1024.0,
    -105.0 / 256.0,
    189.0 / 1024.0,
    -27.0 / 512.0,
    7.0 / 1024.0,
];

/// The split of `r^3` at one radius, with its powers precomputed. Every
/// function takes the squared distance `s = r^2` and returns the kernel's value
/// and its gradient factor `f` (the gradient in `x` of `k(|x - c|)` is
/// `f (x - c)`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SplitKernel {
    radius: f64,
    radius2: f64,
    radius3: f64,
    /// `1 / R^2`: a multiply in the hot loop instead of a divide.
    inverse_radius2: f64,
}

impl SplitKernel {
    pub(crate) fn new(radius: f64) -> Self {
        Self {
            radius,
            radius2: radius * radius,
            radius3: radius * radius * radius,
            inverse_radius2: 1.0 / (radius * radius),
        }
    }

    pub(crate) fn radius(&self) -> f64 {
        self.radius
    }

    /// `R^3 G(t)` and `2 R G'(t)` at `t = s / R^2`.
    #[inline(always)]
    fn smooth(&self, s: f64) -> (f64, f64) {
        let t = s * self.inverse_radius2;
        let (mut g, mut dg) = (0.0, 0.0);
        for (k, b) in SMOOTHING.iter().enumerate().rev() {
            g = g * t + b;
            if k > 0 {
                dg = dg * t + k as f64 * b;
            }
        }
        (self.radius3 * g, 2.0 * self.radius * dg)
    }

    /// The far part's value at squared distance `s`.
    #[inline(always)]
    pub(crate) fn far(&self, s: f64) -> f64 {
        let cube = s * s.sqrt();
        let (smooth, _) = self.smooth(s);
        if s >= self.radius2 {
            cube
        } else {
            smooth
        }
    }

    /// The near part's value and gradient factor at squared distance `s` (zero
    /// from `R` on).
    #[cfg(test)]
    fn near(&self, s: f64) -> (f64, f64) {
        let (value, factor) = self.near_lanes([s; 4]);
        (value[0], factor[0])
    }

    /// [`Self::near`] at four squared distances at once, written lane-wise
    /// (each step an array map) so that it compiles to vector instructions.
    #[inline(always)]
    pub(crate) fn near_lanes(&self, s: [f64; 4]) -> ([f64; 4], [f64; 4]) {
        // Plain loops over the lanes: `array::from_fn` is not always inlined.
        let mut value = [0.0; 4];
        let mut factor = [0.0; 4];
        for l in 0..4 {
            let r = s[l].sqrt();
            let (smooth, dsmooth) = self.smooth(s[l]);
            let inside = s[l] < self.radius2;
            value[l] = if inside { s[l] * r - smooth } else { 0.0 };
            factor[l] = if inside { 3.0 * r - dsmooth } else { 0.0 };
        }
        (value, factor)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parts_add_up_to_the_cube_and_join_smoothly() {
        let kernel = SplitKernel::new(0.7);
        for i in 0..=200 {
            let r = 1.5 * f64::from(i) / 200.0;
            let s = r * r;
            let (near, _) = kernel.near(s);
            assert!((kernel.far(s) + near - r * r * r).abs() < 1e-14, "r = {r}");
        }
        // C^6 at R: the smooth branch's value and derivatives in r agree with r^3.
        let g = |r: f64| kernel.smooth(r * r).0;
        let (r, h) = (0.7, 1e-3);
        let d1 = (g(r + h) - g(r - h)) / (2.0 * h);
        let d2 = (g(r + h) - 2.0 * g(r) + g(r - h)) / (h * h);
        assert!((g(r) - r.powi(3)).abs() < 1e-14);
        assert!((d1 - 3.0 * r * r).abs() < 1e-5, "{d1}");
        assert!((d2 - 6.0 * r).abs() < 1e-4, "{d2}");
        // The gradient factor is the derivative over r.
        let (_, f) = kernel.smooth(0.25);
        let dr = (g(0.5 + 1e-6) - g(0.5 - 1e-6)) / 2e-6;
        assert!((f - dr / 0.5).abs() < 1e-6, "{f} vs {}", dr / 0.5);
    }
}
