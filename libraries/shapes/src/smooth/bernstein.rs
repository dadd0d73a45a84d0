//! Bernstein polynomials of degree 5 on [0, 1] and their derivatives.

/// `B_i^5(t)`, i = 0..5.
pub fn bernstein5(t: f64) -> [f64; 6] {
    let s = 1.0 - t;
    let (t2, s2) = (t * t, s * s);
    let (t3, s3) = (t2 * t, s2 * s);
    [
        s3 * s2,
        5.0 * t * s2 * s2,
        10.0 * t2 * s3,
        10.0 * t3 * s2,
        5.0 * t2 * t2 * s,
        t3 * t2,
    ]
}

/// `B_i^5(t)` and their first derivatives `5 (B_{i-1}^4 - B_i^4)`, without
/// allocating: the inner loop of foot-point projection.
pub fn bernstein5_jet(t: f64) -> ([f64; 6], [f64; 6]) {
    let s = 1.0 - t;
    let b4 = [
        s * s * s * s,
        4.0 * t * s * s * s,
        6.0 * t * t * s * s,
        4.0 * t * t * t * s,
        t * t * t * t,
    ];
    let mut d = [0.0; 6];
    for (i, di) in d.iter_mut().enumerate() {
        let left = if i > 0 { b4[i - 1] } else { 0.0 };
        let right = if i < 5 { b4[i] } else { 0.0 };
        *di = 5.0 * (left - right);
    }
    (bernstein5(t), d)
}

/// The `order`-th derivative of every `B_i^5` at `t` (order 0 to 2).
pub fn bernstein5_derivative(t: f64, order: usize) -> [f64; 6] {
    // d/dt B_i^n = n (B_{i-1}^{n-1} - B_i^{n-1}), applied `order` times.
    let lower = |n: usize| -> Vec<f64> {
        (0..=n)
            .map(|i| binomial(n, i) * t.powi(i as i32) * (1.0 - t).powi((n - i) as i32))
            .collect()
    };
    let n = 5 - order.min(5);
    let mut values = lower(n);
    for degree in n + 1..=5 {
        let mut next = vec![0.0; degree + 1];
        for (i, v) in next.iter_mut().enumerate() {
            let left = if i > 0 { values[i - 1] } else { 0.0 };
            let right = if i < degree { values[i] } else { 0.0 };
            *v = degree as f64 * (left - right);
        }
        values = next;
    }
    let mut out = [0.0; 6];
    out.copy_from_slice(&values);
    out
}

fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn partition_of_unity_and_derivatives_by_differences() {
        for &t in &[0.0, 0.13, 0.5, 0.91, 1.0] {
            let b = bernstein5(t);
            assert!((b.iter().sum::<f64>() - 1.0).abs() < 1e-14);
            for (a, c) in bernstein5_derivative(t, 0).iter().zip(&b) {
                assert!((a - c).abs() < 1e-15);
            }
            let h = 1e-6;
            let (lo, hi) = (bernstein5((t - h).max(0.0)), bernstein5((t + h).min(1.0)));
            let width = (t + h).min(1.0) - (t - h).max(0.0);
            let d = bernstein5_derivative(t, 1);
            for i in 0..6 {
                assert!((d[i] - (hi[i] - lo[i]) / width).abs() < 1e-4, "t {t} i {i}");
            }
            let (b, d1) = bernstein5_jet(t);
            for i in 0..6 {
                assert!((b[i] - bernstein5(t)[i]).abs() < 1e-15);
                assert!((d1[i] - d[i]).abs() < 1e-12);
            }
            // Derivatives of a partition of unity sum to zero.
            assert!(bernstein5_derivative(t, 2).iter().sum::<f64>().abs() < 1e-9);
        }
    }
}
