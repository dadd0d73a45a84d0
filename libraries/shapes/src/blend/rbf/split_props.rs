//! Property tests of the split evaluation ([`super::SplitField`]) against the
//! direct sum ([`super::ExactField`], what `Evaluation::Direct` samples with):
//! random RBFs, cells and batchings (the cache of cell data is reused and
//! evicted between batches, the near centres are padded to whole lanes).

use super::{BatchField, ExactField, Rbf, SplitField};
use glam::DVec3;
use proptest::prelude::*;

/// An RBF through a jittered 4 x 4 x 3 grid of centres (no two closer than a
/// fifth of a step) with arbitrary values, so weights of both signs.
fn random_rbf(jitter: &[(f64, f64, f64)], values: &[f64]) -> Rbf {
    let centres: Vec<DVec3> = (0..48)
        .map(|i| {
            let (x, y, z) = jitter[i];
            let cell = DVec3::new((i % 4) as f64, ((i / 4) % 4) as f64, (i / 16) as f64);
            (cell + 0.4 * DVec3::new(x, y, z)) * 0.3
        })
        .collect();
    Rbf::interpolate(&centres, values).expect("a jittered grid is regular")
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// The far field's degree-5 interpolation with a lattice step `h` of a
    /// sum whose far kernel varies on the scale of the radius `R = 6 h` errs
    /// by about `sum |w| R^3 (h / R)^6` (2e-5 of `sum |w| R^3`) in value and
    /// `sum |w| R^2 (h / R)^5` (1.3e-4 of `sum |w| R^2`) in gradient; the
    /// tolerances below are those bounds (scaled units). A near centre
    /// dropped or counted twice, or a wrong stencil weight, errs by the
    /// order of `|w| R^3` itself.
    #[test]
    fn split_matches_the_direct_sum(
        jitter in prop::collection::vec((-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64), 48),
        values in prop::collection::vec(-0.05..0.05f64, 48),
        cell in 0.01..0.04f64,
        probes in prop::collection::vec((-0.2..1.1f64, -0.2..1.1f64, -0.2..0.8f64), 1..200),
        chunk in 1usize..64,
    ) {
        let rbf = random_rbf(&jitter, &values);
        let points: Vec<DVec3> = probes.iter().map(|&(x, y, z)| DVec3::new(x, y, z)).collect();
        let mut split = SplitField::for_sampling(&rbf, cell);
        let fast: Vec<(f64, DVec3)> = points
            .chunks(chunk)
            .flat_map(|c| split.value_gradients(c))
            .collect();
        let exact = ExactField(&rbf).value_gradients(&points);
        let radius = 12.0 * cell / rbf.scale;
        let mass: f64 = rbf.weights.iter().map(|w| w.abs()).sum();
        let value_tolerance = 2e-5 * mass * radius.powi(3);
        let gradient_tolerance = 1.3e-4 * mass * radius.powi(2) / rbf.scale;
        for ((p, (s, g)), (se, ge)) in points.iter().zip(&fast).zip(&exact) {
            prop_assert!((s - se).abs() <= value_tolerance, "{p}: {s} vs {se} (tolerance {value_tolerance})");
            prop_assert!((*g - *ge).length() <= gradient_tolerance, "{p}: {g} vs {ge} (tolerance {gradient_tolerance})");
        }
        // Values alone, in one batch after the cache is warm: the same numbers.
        let values_again = split.values(&points);
        for (a, (b, _)) in values_again.iter().zip(&fast) {
            prop_assert_eq!(a, b);
        }
    }
}
