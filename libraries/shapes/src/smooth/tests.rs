//! Tests of the smooth fitter: exact recovery of a function of the space,
//! clear errors on bad input, and point location on a planar domain.

use super::*;
use crate::mesh::{catmull_clark, triangle_mesh as m_t, G1Domain};

/// Deterministic numbers in [0, 1).
fn sequence(seed: u64, n: usize) -> Vec<f64> {
    let mut x = seed;
    (0..n)
        .map(|_| {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (x >> 11) as f64 / (1u64 << 53) as f64
        })
        .collect()
}

fn samples(faces: usize, per_face: usize) -> Vec<Sample> {
    let r = sequence(3, 2 * faces * per_face);
    (0..faces * per_face)
        .map(|k| Sample {
            face: k / per_face,
            u: r[2 * k],
            v: r[2 * k + 1],
        })
        .collect()
}

#[test]
fn a_function_of_the_space_is_recovered_exactly() {
    let mesh = catmull_clark(&m_t()).unwrap();
    let fitter = SmoothFitter::new(G1Domain::new(mesh).unwrap()).unwrap();
    let n = fitter.basis.len();
    // A random element of the space, in R^3.
    let weights: Vec<f64> = sequence(9, 3 * n).iter().map(|x| x - 0.5).collect();
    let truth = SmoothSurface {
        dim: 3,
        coefficients: Vec::new(),
        weights: weights.clone(),
    };
    let coefficients = {
        let mut out = vec![0.0; 12 * 36 * 3];
        for (k, f) in fitter.basis.functions.iter().enumerate() {
            for &(index, value) in f {
                for d in 0..3 {
                    out[index * 3 + d] += value * weights[k * 3 + d];
                }
            }
        }
        out
    };
    let truth = SmoothSurface {
        coefficients,
        ..truth
    };
    let s = samples(12, 200);
    let values: Vec<f64> = s
        .iter()
        .flat_map(|p| truth.evaluate(p.face, p.u, p.v))
        .collect();
    let fitted = fitter.fit(&s, &values, 3, 0.0).unwrap();
    let e = fitted.errors(&s, &values);
    assert!(e.max < 1e-9, "{e:?}");
    for (a, b) in fitted.weights.iter().zip(&weights) {
        assert!((a - b).abs() < 1e-7, "{a} vs {b}");
    }
    // Smoothing trades accuracy for energy: errors grow with lambda.
    let smooth = fitter
        .fit(&s, &values, 3, 1e-2)
        .unwrap()
        .errors(&s, &values);
    assert!(smooth.rmse > e.rmse);
}

#[test]
fn bad_input_is_a_named_error() {
    let fitter = SmoothFitter::new(G1Domain::new(m_t()).unwrap()).unwrap();
    let s = samples(3, 100);
    let values = vec![0.5; s.len()];
    assert!(fitter.fit(&s, &values, 1, 0.0).is_ok());
    // Too few points for 72 functions, without smoothing: underdetermined.
    assert!(matches!(
        fitter.fit(&s[..20], &values[..20], 1, 0.0),
        Err(SmoothError::Underdetermined { .. })
    ));
    let mut bad = values.clone();
    bad[7] = f64::NAN;
    assert!(matches!(
        fitter.fit(&s, &bad, 1, 0.0),
        Err(SmoothError::NonFinite { index: 7 })
    ));
    let mut far = s.clone();
    far[3].face = 9;
    assert!(matches!(
        fitter.fit(&far, &values, 1, 0.0),
        Err(SmoothError::NoSuchFace { .. })
    ));
    far = s.clone();
    far[4].u = 1.5;
    assert!(matches!(
        fitter.fit(&far, &values, 1, 0.0),
        Err(SmoothError::OutsidePatch { .. })
    ));
    assert!(matches!(
        fitter.fit(&s, &values, 1, -1.0),
        Err(SmoothError::Lambda(_))
    ));
    assert!(matches!(
        fitter.fit(&s, &values[1..], 1, 0.0),
        Err(SmoothError::ValueCount { .. })
    ));
}

#[test]
fn planar_points_are_located_in_their_face() {
    let mesh = catmull_clark(&m_t()).unwrap();
    let locator = PlanarLocator::new(&mesh).unwrap();
    let v = mesh.vertices();
    for (f, quad) in mesh.faces().iter().enumerate() {
        for (u, w) in [(0.3, 0.6), (0.9, 0.1), (0.5, 0.5)] {
            let p = |k: usize| v[quad[k] as usize];
            let weights = [(1.0 - u) * (1.0 - w), u * (1.0 - w), u * w, (1.0 - u) * w];
            let x: f64 = (0..4).map(|k| weights[k] * p(k)[0]).sum();
            let y: f64 = (0..4).map(|k| weights[k] * p(k)[1]).sum();
            let s = locator.locate(x, y).expect("inside");
            assert_eq!(s.face, f);
            assert!((s.u - u).abs() < 1e-9 && (s.v - w).abs() < 1e-9);
        }
    }
    assert!(locator.locate(-5.0, 0.0).is_none());
    assert!(matches!(
        locator.locate_all(&[[0.5, 0.2], [10.0, 10.0]]),
        Err(SmoothError::OutsideDomain { index: 1, .. })
    ));
}
