//! Timings of the hot queries on a fitted 20 x 20 terrain surrogate (ignored by
//! default; run with `--release -- --ignored --nocapture`). They still check
//! their answers, so they cannot pass on garbage.

use super::fixtures::{fitted, rng, terrain, to_dvec};
use crate::query::{
    BoundOptions, BoundQuery, CellFilter, Classify, ParamRect, PointClass, Ray, RayCast, SideView,
};
use crate::{Side, Sides};
use glam::DVec3;
use rand::Rng;
use std::time::Instant;

fn per_query(start: Instant, n: usize) -> f64 {
    start.elapsed().as_secs_f64() * 1e6 / n as f64
}

#[test]
#[ignore = "timing; run in release"]
fn ray_bound_and_classify_throughput() {
    let points = terrain(300_000);
    let sur = fitted(&points, Sides::Upper, [0.0, 0.0, -1.0], 20);
    let view = SideView::new(&sur, Side::Upper).unwrap();
    let mut r = rng(3);
    let n = 20_000;
    let rays: Vec<Ray> = (0..n)
        .map(|_| Ray {
            origin: DVec3::new(r.random_range(-4.0..4.0), r.random_range(-3.0..3.0), 3.0),
            direction: DVec3::new(r.random_range(-1.0..1.0), r.random_range(-1.0..1.0), -1.5),
        })
        .collect();
    let start = Instant::now();
    let hits: Vec<_> = rays
        .iter()
        .map(|ray| view.first_hit(ray, 20.0).unwrap())
        .collect();
    let ray_us = per_query(start, n);
    let hit_count = hits.iter().flatten().count();
    for hit in hits.iter().flatten() {
        let (s, t, w) = view.locate(hit.point);
        assert!((view.surface().eval(s, t) - w).abs() < 1e-9);
    }
    assert!(
        hit_count > n / 2,
        "downward rays from above mostly hit: {hit_count}"
    );

    let rects: Vec<ParamRect> = (0..n)
        .map(|_| {
            let (s, t) = (r.random_range(0.0..19.0), r.random_range(0.0..19.0));
            ParamRect {
                s: [s, s + r.random_range(0.0..2.0)],
                t: [t, t + r.random_range(0.0..2.0)],
            }
        })
        .collect();
    let mut timings = Vec::new();
    for refine in [0, 2] {
        let options = BoundOptions {
            cells: CellFilter::Kept,
            refine,
        };
        let start = Instant::now();
        let ranges: Vec<_> = rects
            .iter()
            .map(|rect| view.range_over_params(*rect, options).unwrap())
            .collect();
        timings.push(per_query(start, n));
        assert!(ranges.iter().flatten().all(|range| range.min <= range.max));
    }

    let start = Instant::now();
    let below = points
        .iter()
        .filter(|p| matches!(view.classify(to_dvec(p)), PointClass::Below { .. }))
        .count();
    let classify_us = per_query(start, points.len());
    assert_eq!(below, points.len());
    println!(
        "ray: {ray_us:.2} us/ray ({hit_count}/{n} hit); bound: {:.2} us (refine 0), {:.2} us (refine 2); \
         classify: {:.3} us/point",
        timings[0], timings[1], classify_us
    );
}
