//! Rim detection on random scans (issue 12): success rates over many seeds per
//! shape of `shroud_sim::scanned_parts`, and each refusal's diagnosis on a
//! shape that triggers it, down to the blend's error message.

use shroud_geometry::cloud::{
    find_rim, BoundaryFailure, BoundaryLoop, BoundaryParams, NeighbourIndex,
};
use shroud_shapes::blend::{BlendError, Child, Prepared};
use shroud_sim::scanned_parts::ScannedShape;

/// The hemisphere: radius 0.3, 6,000 points.
const RADIUS: f64 = 0.3;
const POINTS: usize = 6_000;
/// Draws per shape; at least `NEEDED` of them must come out right (85 %;
/// `examples/boundary_sweep.rs` measures the rates).
const SEEDS: u64 = 20;
const NEEDED: usize = 17;

fn detect(
    shape: ScannedShape,
    points: usize,
    seed: u64,
) -> (NeighbourIndex, Result<BoundaryLoop, BoundaryFailure>) {
    let index = NeighbourIndex::from_f32(&shape.sample(RADIUS, points, seed));
    let rim = find_rim(&index, &BoundaryParams::default());
    (index, rim)
}

/// Draws of `shape` whose detected loop follows its rim.
fn rims_found(shape: ScannedShape) -> usize {
    (0..SEEDS)
        .filter(|&seed| {
            let (index, rim) = detect(shape, POINTS, seed);
            rim.is_ok_and(|rim| {
                shape.follows_rim(
                    rim.indices.iter().map(|&i| index.points()[i].to_array()),
                    RADIUS,
                )
            })
        })
        .count()
}

fn assert_rims_found(shape: ScannedShape) {
    let found = rims_found(shape);
    assert!(
        found >= NEEDED,
        "{}: rim found in {found} of {SEEDS} draws",
        shape.name()
    );
}

#[test]
fn hemisphere_rims_are_found() {
    assert_rims_found(ScannedShape::Hemisphere);
}

#[test]
fn paraboloid_rims_are_found() {
    assert_rims_found(ScannedShape::Paraboloid);
}

#[test]
fn disc_rims_are_found() {
    assert_rims_found(ScannedShape::Disc);
}

#[test]
fn noisy_cap_rims_are_found() {
    assert_rims_found(ScannedShape::NoisyCap);
}

#[test]
fn lopsided_cap_rims_are_found() {
    assert_rims_found(ScannedShape::LopsidedCap);
}

#[test]
fn bands_have_several_loops() {
    let refused = (0..SEEDS)
        .filter(|&seed| {
            matches!(
                detect(ScannedShape::Band, POINTS, seed).1,
                Err(BoundaryFailure::SeveralLoops { ref lengths, .. }) if lengths.len() == 2
            )
        })
        .count();
    assert!(refused >= NEEDED, "several loops in {refused} of {SEEDS}");
}

#[test]
fn closed_spheres_have_no_gap() {
    let refused = (0..SEEDS)
        .filter(|&seed| {
            matches!(
                detect(ScannedShape::ClosedSphere, POINTS, seed).1,
                Err(BoundaryFailure::NoGap { .. })
            )
        })
        .count();
    assert!(refused >= NEEDED, "no gap in {refused} of {SEEDS}");
}

#[test]
fn a_sparse_cap_is_too_sparse() {
    for seed in 0..10 {
        let (_, rim) = detect(ScannedShape::Hemisphere, 80, seed);
        assert!(
            matches!(rim, Err(BoundaryFailure::TooSparse { points: 80, k: 20, suggested, .. }) if suggested > 80),
            "seed {seed}: {rim:?}"
        );
    }
}

/// The blend's error names the cloud, the diagnosis and its numbers.
#[test]
fn the_blend_says_why_and_what_to_do() {
    let child = |shape: ScannedShape, points: usize| {
        let cloud = Prepared::new(&shape.sample(RADIUS, points, 1), "child", 12).unwrap();
        Child::new(cloud, None, &BoundaryParams::default()).unwrap_err()
    };
    let cases = [
        (
            child(ScannedShape::ClosedSphere, 3_000),
            "no gap",
            "cut it open",
        ),
        (
            child(ScannedShape::Hemisphere, 80),
            "too sparse",
            "denser scan",
        ),
        (
            child(ScannedShape::Band, 3_000),
            "2 open boundary loops",
            "trim the part",
        ),
    ];
    for (err, why, what) in cases {
        assert!(
            matches!(err, BlendError::NoBoundaryLoop { what: "child", .. }),
            "{err:?}"
        );
        let text = err.to_string();
        assert!(text.starts_with("the child cloud"), "{text}");
        assert!(text.contains(why) && text.contains(what), "{text}");
        assert!(text.contains("polygon of interest"), "{text}");
    }
}
