//! The thin-plate energy (eq. 27) of one biquintic patch as a quadratic form on
//! its 36 Bernstein coefficients, in the patch's own parameters:
//! `E = c^T G c`, `G = D2 (x) M + 2 D1 (x) D1 + M (x) D2` with the 1D Gram
//! matrices `M = int B_i B_k`, `D1 = int B_i' B_k'`, `D2 = int B_i'' B_k''`.

use super::bernstein::bernstein5_derivative;

/// Gauss-Legendre nodes and weights on [0, 1], exact to degree 11.
const GAUSS6: [(f64, f64); 6] = [
    (0.033_765_242_898_423_98, 0.085_662_246_189_585_17),
    (0.169_395_306_766_867_74, 0.180_380_786_524_069_3),
    (0.380_690_406_958_401_5, 0.233_956_967_286_345_52),
    (0.619_309_593_041_598_5, 0.233_956_967_286_345_52),
    (0.830_604_693_233_132_3, 0.180_380_786_524_069_3),
    (0.966_234_757_101_576, 0.085_662_246_189_585_17),
];

fn gram_1d(order: usize) -> [[f64; 6]; 6] {
    let mut g = [[0.0; 6]; 6];
    for &(t, w) in &GAUSS6 {
        let d = bernstein5_derivative(t, order);
        for i in 0..6 {
            for k in 0..6 {
                g[i][k] += w * d[i] * d[k];
            }
        }
    }
    g
}

/// The 36 x 36 thin-plate Gram matrix, row-major, coefficient `(i, j)` at `6 j + i`.
pub fn thin_plate_gram() -> Vec<f64> {
    let (m, d1, d2) = (gram_1d(0), gram_1d(1), gram_1d(2));
    let mut g = vec![0.0; 36 * 36];
    for j in 0..6 {
        for i in 0..6 {
            for l in 0..6 {
                for k in 0..6 {
                    let value = d2[i][k] * m[j][l] + 2.0 * d1[i][k] * d1[j][l] + m[i][k] * d2[j][l];
                    g[(6 * j + i) * 36 + 6 * l + k] = value;
                }
            }
        }
    }
    g
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Coefficients of a polynomial in the degree-5 Bernstein basis by sampling.
    fn energy(coefficients: &[f64]) -> f64 {
        let g = thin_plate_gram();
        (0..36)
            .map(|a| {
                (0..36)
                    .map(|b| coefficients[a] * g[a * 36 + b] * coefficients[b])
                    .sum::<f64>()
            })
            .sum()
    }

    #[test]
    fn affine_functions_cost_nothing_and_x_squared_costs_its_integral() {
        // f = u: Bernstein coefficients i / 5 (linear precision).
        let linear: Vec<f64> = (0..36).map(|k| (k % 6) as f64 / 5.0).collect();
        assert!(energy(&linear).abs() < 1e-12);
        // f = u^2: coefficients i (i - 1) / 20; f_uu = 2, energy = 4.
        let square: Vec<f64> = (0..36)
            .map(|k| {
                let i = (k % 6) as f64;
                i * (i - 1.0) / 20.0
            })
            .collect();
        assert!((energy(&square) - 4.0).abs() < 1e-10);
        // f = u v: coefficients i j / 25; f_uv = 1, energy = 2.
        let product: Vec<f64> = (0..36).map(|k| ((k % 6) * (k / 6)) as f64 / 25.0).collect();
        assert!((energy(&product) - 2.0).abs() < 1e-10);
    }
}
