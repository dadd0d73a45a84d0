//! Tests of parametric fitting: border-crossing parameter moves, foot points,
//! surface derivatives and parameter correction.

use super::*;
use crate::mesh::{catmull_clark, cube_mesh, rectangle_mesh, sample_limit_surface, G1Domain};
use glam::DVec3;
use shroud_geometry::math::fibonacci_sphere;

#[test]
fn parameters_past_a_side_continue_in_the_neighbour() {
    let mesh = rectangle_mesh([0.0; 2], [3.0; 2], 3).unwrap();
    let patches = BilinearPatches::new(&mesh);
    let adjacency = PatchAdjacency::new(&mesh);
    // From the centre square, moves past each side and past a corner land on
    // the point with the same position in the plane.
    for (u, v) in [
        (1.3, 0.4),
        (-0.2, 0.7),
        (0.5, 1.25),
        (0.1, -0.4),
        (1.2, 1.3),
        (-0.3, -0.1),
    ] {
        let s = adjacency.wrap(4, u, v);
        assert_ne!(s.face, 4, "({u}, {v})");
        let want = DVec3::new(1.0 + u, 1.0 + v, 0.0);
        let got = patches.jet(s.face, s.u, s.v)[0];
        assert!((got - want).length() < 1e-12, "({u}, {v}): {got} vs {want}");
    }
    // Inside, nothing moves; past the domain's boundary, clamped.
    assert_eq!(
        adjacency.wrap(4, 0.3, 0.6),
        Sample {
            face: 4,
            u: 0.3,
            v: 0.6
        }
    );
    assert_eq!(
        adjacency.wrap(0, -0.5, 0.2),
        Sample {
            face: 0,
            u: 0.0,
            v: 0.2
        }
    );
    // On a closed mesh a move past a side lands strictly inside the
    // neighbour, at the depth it went past (nothing is clamped).
    let sphere = cube_sphere(1).unwrap();
    let adjacency = PatchAdjacency::new(&sphere);
    let inside = |t: f64| t > 0.0 && t < 1.0;
    for f in 0..sphere.face_count() {
        for (u, v, depth) in [(1.4, 0.5, 0.4), (0.5, 1.9, 0.9), (-0.25, 0.3, 0.25)] {
            let s = adjacency.wrap(f, u, v);
            assert_ne!(s.face, f);
            assert!(inside(s.u) && inside(s.v), "{f} ({u}, {v}): {s:?}");
            let from_side = [s.v, 1.0 - s.u, 1.0 - s.v, s.u];
            assert!(from_side.iter().any(|d| (d - depth).abs() < 1e-12), "{s:?}");
        }
    }
}

#[test]
fn points_of_the_limit_surface_get_their_own_parameters_back() {
    // A domain mesh in space and points of its Catmull-Clark limit surface at
    // known parameters: the locator's foot points on its stand-in surface
    // give those parameters back, up to the stand-in's small deviation.
    let mesh = catmull_clark(&cube_mesh()).unwrap();
    let locator = SurfaceLocator::new(&mesh).unwrap();
    let cloud = sample_limit_surface(&mesh, 2000, 5, 5).unwrap();
    let mut same_face = 0;
    for s in &cloud {
        let found = locator.locate(s.point).unwrap();
        if found.face == s.face {
            same_face += 1;
            let off = (found.u - s.u).abs() + (found.v - s.v).abs();
            assert!(off < 0.02, "{s:?} -> {found:?}");
        }
    }
    // Points within rounding of an edge may land on the neighbour.
    assert!(same_face > 1980, "{same_face}");
    assert!(locator.locate([f64::NAN, 0.0, 0.0]).is_none());
}

#[test]
fn surface_derivatives_match_differences() {
    let mesh = cube_sphere(1).unwrap();
    let fitter = SmoothFitter::new(G1Domain::new(mesh).unwrap()).unwrap();
    let surface = sphere_surface(&fitter);
    let h = 1e-6;
    for (face, u, v) in [(0, 0.3, 0.6), (7, 0.5, 0.1), (19, 0.9, 0.95)] {
        let [_, du, dv] = surface.jet(face, u, v);
        let at = |u: f64, v: f64| DVec3::from_slice(&surface.evaluate(face, u, v));
        let fu = (at(u + h, v) - at(u - h, v)) / (2.0 * h);
        let fv = (at(u, v + h) - at(u, v - h)) / (2.0 * h);
        assert!((fu - du).length() < 1e-6 && (fv - dv).length() < 1e-6);
    }
}

/// The unit sphere fitted in R^3 over the cube-sphere (central projection).
fn sphere_surface(fitter: &SmoothFitter) -> SmoothSurface {
    let parametrisation = Parametrisation::radial(&fitter.domain.mesh);
    let points: Vec<[f64; 3]> = fibonacci_sphere(4000)
        .iter()
        .map(|d| d.to_array())
        .collect();
    let (samples, _) = parametrisation.sample_all(&points).unwrap();
    let values: Vec<f64> = points.iter().flatten().copied().collect();
    fitter.fit(&samples, &values, 3, 0.0).unwrap()
}

fn sphere_fitter() -> SmoothFitter {
    let mesh = cube_sphere(1).unwrap();
    SmoothFitter::new(G1Domain::new(mesh).unwrap()).unwrap()
}

/// `per_face` random points of the sphere surface of the space on each
/// patch, given with parameters shifted by up to `shift` / 2 (across
/// borders), and the points (x, y, z each).
fn shifted_samples(
    fitter: &SmoothFitter,
    per_face: usize,
    shift: f64,
    seed: f64,
) -> (Vec<Sample>, Vec<f64>) {
    let truth = sphere_surface(fitter);
    let faces = fitter.domain.mesh.face_count();
    let mut x = seed;
    let mut next = || {
        x = (x * 9973.0 + 0.377).fract();
        x
    };
    let mut samples = Vec::new();
    let mut points = Vec::new();
    for k in 0..faces * per_face {
        let (face, u, v) = (k % faces, next(), next());
        points.extend_from_slice(&truth.evaluate(face, u, v));
        let (du, dv) = (shift * (next() - 0.5), shift * (next() - 0.5));
        samples.push(fitter.adjacency().wrap(face, u + du, v + dv));
    }
    (samples, points)
}

#[test]
fn parameter_correction_recovers_a_surface_of_the_space() {
    // Points of a surface of the space, given with parameters shifted by up
    // to a fifth of a patch (across borders): the first fit is poor, the
    // corrections bring it back to the surface.
    let fitter = sphere_fitter();
    let (samples, points) = shifted_samples(&fitter, 300, 0.4, 0.123);
    let fit = fitter.fit_parametric(&samples, &points, 0.0, 3).unwrap();
    assert_eq!(fit.rounds.len(), 4);
    let (first, last) = (fit.rounds[0], fit.rounds[3]);
    assert!(first.rmse > 1e-3, "{first:?}");
    assert!(last.rmse < 0.05 * first.rmse, "{first:?} -> {last:?}");
    assert!(last.max < first.max, "{first:?} -> {last:?}");
    // Corrected parameters are foot points: the residual is normal to the
    // surface they were projected on.
    let mut feet = fit.samples.clone();
    correct_parameters(&fit.surface, fitter.adjacency(), &mut feet, &points);
    for (s, p) in feet.iter().zip(points.chunks(3)).step_by(97) {
        let [q, du, dv] = fit.surface.jet(s.face, s.u, s.v);
        let r = DVec3::from_slice(p) - q;
        let inside = s.u > 0.0 && s.u < 1.0 && s.v > 0.0 && s.v < 1.0;
        if inside && r.length() > 1e-9 {
            let n = du.cross(dv).normalize();
            assert!(r.normalize().dot(n).abs() > 0.99, "{s:?}");
        }
    }
}

#[test]
fn parametric_sampling_names_bad_points() {
    let mesh = cube_sphere(1).unwrap();
    let parametrisation = Parametrisation::parametric(&mesh).unwrap();
    assert_eq!(
        (parametrisation.kind(), parametrisation.dim()),
        ("parametric", 3)
    );
    let (samples, values) = parametrisation
        .sample_all(&[[2.0, 0.1, 0.0], [0.0, 0.0, -3.0]])
        .unwrap();
    assert_eq!((samples.len(), values.len()), (2, 6));
    assert_eq!(&values[..3], &[2.0, 0.1, 0.0]);
    assert!(matches!(
        parametrisation.sample_all(&[[0.0, 0.0, 1.0], [0.0, f64::INFINITY, 0.0]]),
        Err(SmoothError::NonFinitePoint { index: 1 })
    ));
}

#[test]
fn normals_of_a_fitted_surface_are_continuous_across_every_edge() {
    // The unit sphere fitted in R^3 over the cube-sphere, whose eight
    // valence-3 EVs make its edges G1 rather than C1: on both sides of every
    // edge, the same point and the same unit normal.
    let mesh = cube_sphere(1).unwrap();
    let fitter = SmoothFitter::new(G1Domain::new(mesh).unwrap()).unwrap();
    let surface = sphere_surface(&fitter);
    let adjacency = fitter.adjacency();
    let normal = |s: Sample| {
        let [p, du, dv] = surface.jet(s.face, s.u, s.v);
        (p, du.cross(dv).normalize())
    };
    let mut checked = 0;
    for face in 0..fitter.domain.mesh.face_count() {
        for a in [0.0, 0.13, 0.5, 0.71, 1.0] {
            // Each side, and a step of 1e-13 past it into the neighbour.
            for (u, v, du, dv) in [
                (a, 0.0, 0.0, -1.0),
                (1.0, a, 1.0, 0.0),
                (a, 1.0, 0.0, 1.0),
                (0.0, a, -1.0, 0.0),
            ] {
                let across = adjacency.wrap(face, u + 1e-13 * du, v + 1e-13 * dv);
                assert_ne!(across.face, face);
                let (p, n) = normal(Sample { face, u, v });
                let (q, m) = normal(across);
                assert!((p - q).length() < 1e-10, "face {face} ({u}, {v})");
                assert!(
                    n.dot(m) > 1.0 - 1e-9,
                    "face {face} ({u}, {v}): {}",
                    n.dot(m)
                );
                checked += 1;
            }
        }
    }
    assert_eq!(checked, 24 * 5 * 4);
}

#[test]
fn a_warm_start_on_the_previous_fit_saves_corrections() {
    // The same object scanned twice: starting the second fit from the first
    // one's surface reaches, with one correction, below what a cold start
    // reaches with one.
    let fitter = sphere_fitter();
    let faces = fitter.domain.mesh.face_count();
    let (samples, points) = shifted_samples(&fitter, 200, 0.3, 0.77);
    let first = fitter.fit_parametric(&samples, &points, 0.0, 3).unwrap();
    let cold = fitter.fit_parametric(&samples, &points, 0.0, 1).unwrap();
    let warm = fitter
        .fit_parametric_warm(&first.surface, &samples, &points, 0.0, 1)
        .unwrap();
    // Without any correction the warm fit is 30 times closer than the cold
    // one; after one it is below the cold fit after three.
    assert!(
        warm.rounds[0].rmse < 0.05 * cold.rounds[0].rmse,
        "{:?}",
        warm.rounds
    );
    assert!(
        warm.rounds[1].rmse < first.rounds[3].rmse,
        "{:?} {:?}",
        warm.rounds,
        first.rounds
    );
    let cold = cold.rounds[1].rmse;
    // A surface of another space is no warm start: the cold fit.
    let other = SmoothSurface {
        dim: 1,
        coefficients: vec![0.0; faces * 36],
        weights: vec![0.0; fitter.basis.len()],
    };
    let ignored = fitter
        .fit_parametric_warm(&other, &samples, &points, 0.0, 1)
        .unwrap();
    assert_eq!(ignored.rounds[1].rmse, cold);
}
