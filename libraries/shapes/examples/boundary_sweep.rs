//! The boundary sweep (issue 12): how often the blend finds a part's rim, its
//! polygon of interest (paper 001, Section 3.1), on random scans: every shape
//! of `shroud_sim::scanned_parts`, many seeds each, the outcomes counted (the
//! rim found, a loop elsewhere, or which refusal) and the detection timed (the
//! kd-tree is built beforehand, as a drag session does once per part).
//!
//! `cargo run -p shroud-shapes --profile test --example boundary_sweep [-- DRAWS POINTS]`
//! (defaults 200 draws of 6,000 points).

use shroud_geometry::cloud::{BoundaryFailure, BoundaryParams, NeighbourIndex};
use shroud_shapes::blend::{BlendError, PolygonOfInterest};
use shroud_sim::scanned_parts::{ScannedShape, SCANNED_SHAPES};
use std::collections::BTreeMap;
use std::time::Instant;

/// Size of every shape: the hemisphere of radius 0.3.
const RADIUS: f64 = 0.3;

/// What one detection gave.
fn outcome(shape: ScannedShape, result: &Result<PolygonOfInterest, BlendError>) -> &'static str {
    match result {
        Ok(polygon) => {
            let vertices = polygon.vertices().iter().map(|v| v.to_array());
            if shape.follows_rim(vertices, RADIUS) {
                "rim found"
            } else {
                "loop off the rim"
            }
        }
        Err(BlendError::NoBoundaryLoop { reason, .. }) => match reason {
            BoundaryFailure::TooSparse { .. } => "too sparse",
            BoundaryFailure::NoGap { .. } => "no gap",
            BoundaryFailure::OpenRim { .. } => "open rim",
            BoundaryFailure::SeveralLoops { .. } => "several loops",
        },
        Err(_) => "other error",
    }
}

/// The outcome a correct detector gives on `shape`.
fn expected(shape: ScannedShape) -> &'static str {
    match shape.rims() {
        0 => "no gap",
        1 => "rim found",
        _ => "several loops",
    }
}

/// Outcome counts and the median detection time (ms) over `draws` seeds.
fn sweep(
    shape: ScannedShape,
    draws: u64,
    points: usize,
    params: &BoundaryParams,
) -> (BTreeMap<&'static str, usize>, f64) {
    let mut counts = BTreeMap::new();
    let mut times = Vec::new();
    for seed in 0..draws {
        let index = NeighbourIndex::from_f32(&shape.sample(RADIUS, points, seed));
        let start = Instant::now();
        let result = PolygonOfInterest::detect(&index, params, "child");
        times.push(start.elapsed().as_secs_f64() * 1e3);
        if std::env::var_os("SWEEP_VERBOSE").is_some() && outcome(shape, &result) != expected(shape)
        {
            match &result {
                Err(e) => eprintln!("{} seed {seed}: {e}", shape.name()),
                Ok(p) => eprintln!(
                    "{} seed {seed}: loop {:?}",
                    shape.name(),
                    &p.vertices()[..3]
                ),
            }
        }
        *counts.entry(outcome(shape, &result)).or_insert(0) += 1;
    }
    times.sort_by(f64::total_cmp);
    (
        counts,
        times.get(times.len() / 2).copied().unwrap_or(f64::NAN),
    )
}

fn main() {
    let mut args = std::env::args().skip(1);
    let draws: u64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(200);
    let points: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(6_000);
    let mut params = BoundaryParams::default();
    if let Some(k) = args.next().and_then(|a| a.parse().ok()) {
        params.k = k;
    }
    if let Some(score) = args.next().and_then(|a| a.parse().ok()) {
        params.min_score = score;
    }
    if let Some(link) = args.next().and_then(|a| a.parse().ok()) {
        params.link = link;
    }
    println!(
        "Rim detection on random scans of radius {RADIUS}, {points} points, seeds 0..{draws}:\n"
    );
    println!("| shape | rims | expected | as expected | other outcomes | median ms |");
    println!("|---|---:|---|---:|---|---:|");
    for shape in SCANNED_SHAPES {
        let (counts, ms) = sweep(shape, draws, points, &params);
        let want = expected(shape);
        let hits = counts.get(want).copied().unwrap_or(0);
        let others: Vec<String> = counts
            .iter()
            .filter(|(k, _)| **k != want)
            .map(|(k, n)| format!("{k}: {n}"))
            .collect();
        println!(
            "| {} | {} | {want} | {hits} / {draws} | {} | {ms:.1} |",
            shape.name(),
            shape.rims(),
            others.join(", ")
        );
    }
}
