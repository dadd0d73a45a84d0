//! Bounds against dense sampling: conservative, tight on constants, tighter with
//! refinement, and well behaved on tiny, degenerate, reversed or outside rectangles.

use super::fixtures::{assemble, domain, random_coefficients, random_surrogate, random_trim, rng};
use crate::query::{
    BoundOptions, BoundQuery, CellFilter, HeightQuery, HeightRange, ParamRect, QueryError,
    SideView, UvRect, MAX_REFINE,
};
use crate::{Side, TrimMask};
use rand::Rng;

const ALL_CELLS: BoundOptions = BoundOptions {
    cells: CellFilter::All,
    refine: 0,
};

/// Sampled min and max of the kept surface over the clipped rectangle.
fn sampled(view: &SideView, rect: ParamRect, n: usize) -> Option<(f64, f64)> {
    let (cs, ct) = view.cells();
    let clip = |x: [f64; 2], hi: usize| [x[0].min(x[1]).max(0.0), x[0].max(x[1]).min(hi as f64)];
    let (s, t) = (clip(rect.s, cs), clip(rect.t, ct));
    if s[0] > s[1] || t[0] > t[1] {
        return None;
    }
    let mut out: Option<(f64, f64)> = None;
    for i in 0..=n {
        for j in 0..=n {
            let (a, b) = (i as f64 / n as f64, j as f64 / n as f64);
            if let Some(f) =
                view.height_at_param(s[0] + a * (s[1] - s[0]), t[0] + b * (t[1] - t[0]))
            {
                out = Some(out.map_or((f, f), |(lo, hi)| (lo.min(f), hi.max(f))));
            }
        }
    }
    out
}

fn random_rect(r: &mut impl Rng, cs: f64, ct: f64) -> ParamRect {
    ParamRect {
        s: [
            r.random_range(-1.0..cs + 1.0),
            r.random_range(-1.0..cs + 1.0),
        ],
        t: [
            r.random_range(-1.0..ct + 1.0),
            r.random_range(-1.0..ct + 1.0),
        ],
    }
}

#[test]
fn bounds_contain_dense_samples_over_random_rectangles() {
    let (cols, rows) = (8, 6);
    let trim = random_trim(cols - 1, rows - 1, 9);
    let sur = assemble(
        [1.0, -2.0, -2.0],
        domain(cols, rows),
        trim,
        [Some(random_coefficients(cols * rows, 9)), None],
    );
    let view = SideView::new(&sur, Side::Upper).unwrap();
    let mut r = rng(21);
    let mut checked = 0;
    for _ in 0..300 {
        let rect = random_rect(&mut r, 7.0, 5.0);
        for cells in [CellFilter::Kept, CellFilter::All] {
            for refine in [0, 2] {
                let range = view
                    .range_over_params(rect, BoundOptions { cells, refine })
                    .unwrap();
                let Some((lo, hi)) = sampled(&view, rect, 40) else {
                    continue;
                };
                let range = range.expect("kept samples imply a range");
                assert!(
                    range.min <= lo && hi <= range.max,
                    "{rect:?} {cells:?}/{refine}: {range:?} vs [{lo}, {hi}]"
                );
                checked += 1;
            }
        }
    }
    assert!(checked > 500);
}

#[test]
fn constant_surfaces_are_bounded_by_their_constant() {
    let sur = assemble(
        [0.0, 0.0, -1.0],
        domain(5, 5),
        TrimMask::full(4, 4),
        [Some(vec![-2.5; 25]), None],
    );
    let view = SideView::new(&sur, Side::Upper).unwrap();
    let range = view
        .range_over_params(
            ParamRect {
                s: [0.3, 3.7],
                t: [1.0, 2.0],
            },
            ALL_CELLS,
        )
        .unwrap()
        .unwrap();
    assert!(
        (range.min + 2.5).abs() < 1e-13 && (range.max + 2.5).abs() < 1e-13,
        "{range:?}"
    );
    assert!(range.min <= -2.5 && range.max >= -2.5);
}

#[test]
fn refinement_tightens_monotonically_and_stays_conservative() {
    let sur = random_surrogate(7, 7, [0.0, 0.0, -1.0], 5);
    let view = SideView::new(&sur, Side::Upper).unwrap();
    let rect = ParamRect {
        s: [0.7, 4.2],
        t: [5.5, 1.1],
    };
    let (lo, hi) = sampled(&view, rect, 200).unwrap();
    let mut previous: Option<HeightRange> = None;
    for refine in 0..=5 {
        let range = view
            .range_over_params(
                rect,
                BoundOptions {
                    cells: CellFilter::All,
                    refine,
                },
            )
            .unwrap()
            .unwrap();
        assert!(range.min <= lo && hi <= range.max);
        if let Some(p) = previous {
            assert!(
                range.max <= p.max + 1e-12 && range.min >= p.min - 1e-12,
                "refine {refine}"
            );
        }
        previous = Some(range);
    }
    let coarse = view.range_over_params(rect, ALL_CELLS).unwrap().unwrap();
    let fine = previous.unwrap();
    assert!(
        fine.max - hi < 0.1 * (coarse.max - hi),
        "refinement closes most of the gap"
    );
    assert!(fine.max - hi < 1e-2 && lo - fine.min < 1e-2);
}

#[test]
fn control_nets_are_tighter_than_spline_coefficients() {
    let sur = random_surrogate(6, 6, [0.0, 0.0, -1.0], 6);
    let view = SideView::new(&sur, Side::Upper).unwrap();
    for (h, g) in [(0, 0), (2, 3), (4, 4)] {
        let c = view.surface().cell_coefficients(h, g);
        let (lo, hi) = c
            .iter()
            .flatten()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            });
        let cell = ParamRect {
            s: [h as f64, h as f64 + 1.0],
            t: [g as f64, g as f64 + 1.0],
        };
        let range = view.range_over_params(cell, ALL_CELLS).unwrap().unwrap();
        assert!(range.max <= hi + 1e-12 && range.min >= lo - 1e-12);
        assert!(
            range.max - range.min < hi - lo,
            "strictly tighter on random data"
        );
    }
}

#[test]
fn tiny_and_degenerate_rectangles_bound_the_point_value() {
    let sur = random_surrogate(6, 6, [0.0, 0.0, -1.0], 7);
    let view = SideView::new(&sur, Side::Upper).unwrap();
    for rect in [
        ParamRect {
            s: [2.3, 2.3],
            t: [1.7, 1.7],
        },
        ParamRect {
            s: [2.3, 2.3 + 1e-9],
            t: [1.7, 1.7 + 1e-9],
        },
        ParamRect {
            s: [3.0, 3.0],
            t: [4.0, 4.0],
        },
        ParamRect {
            s: [5.0, 5.0],
            t: [0.0, 0.0],
        },
        ParamRect {
            s: [1.0, 4.0],
            t: [2.0, 2.0],
        },
    ] {
        let range = view
            .range_over_params(rect, BoundOptions::default())
            .unwrap()
            .unwrap();
        for (s, t) in [(rect.s[0], rect.t[0]), (rect.s[1], rect.t[1])] {
            let f = view.surface().eval(s, t);
            assert!(
                range.min <= f && f <= range.max,
                "{rect:?}: {f} not in {range:?}"
            );
        }
        if rect.s[1] - rect.s[0] < 1e-8 {
            assert!(range.max - range.min < 1e-8, "{rect:?}: {range:?}");
        }
    }
}

#[test]
fn rectangles_are_clipped_to_the_domain_and_corners_may_be_reversed() {
    let sur = random_surrogate(6, 5, [0.0, 0.0, -1.0], 8);
    let view = SideView::new(&sur, Side::Upper).unwrap();
    let inside = view
        .range_over_params(
            ParamRect {
                s: [0.0, 1.5],
                t: [0.5, 4.0],
            },
            ALL_CELLS,
        )
        .unwrap();
    let partly = view
        .range_over_params(
            ParamRect {
                s: [-3.0, 1.5],
                t: [0.5, 10.0],
            },
            ALL_CELLS,
        )
        .unwrap();
    let reversed = view
        .range_over_params(
            ParamRect {
                s: [1.5, -3.0],
                t: [10.0, 0.5],
            },
            ALL_CELLS,
        )
        .unwrap();
    assert_eq!(inside, partly);
    assert_eq!(inside, reversed);
    let outside = ParamRect {
        s: [6.0, 9.0],
        t: [0.0, 1.0],
    };
    assert_eq!(view.range_over_params(outside, ALL_CELLS).unwrap(), None);
    assert_eq!(view.upper_bound(outside, ALL_CELLS).unwrap(), None);
    let whole = ParamRect {
        s: [0.0, 5.0],
        t: [0.0, 4.0],
    };
    assert!(view.upper_bound(whole, ALL_CELLS).unwrap().unwrap() >= inside.unwrap().max);
    assert!(view.lower_bound(whole, ALL_CELLS).unwrap().unwrap() <= inside.unwrap().min);
}

#[test]
fn trimmed_cells_are_skipped_only_when_asked() {
    let (cols, rows) = (4, 3);
    let mut c = vec![0.0; cols * rows];
    c[cols - 1] = 10.0; // high corner at s = 3, t = 0: lifts cell (2, 0) most
    let mut trim = TrimMask::full(cols - 1, rows - 1);
    trim.bits[2] = 0; // cell (2, 0)
    let sur = assemble([0.0, 0.0, -1.0], domain(cols, rows), trim, [Some(c), None]);
    let view = SideView::new(&sur, Side::Upper).unwrap();
    let rect = ParamRect {
        s: [1.0, 3.0],
        t: [0.0, 1.0],
    };
    let kept = view
        .range_over_params(rect, BoundOptions::default())
        .unwrap()
        .unwrap();
    let all = view.range_over_params(rect, ALL_CELLS).unwrap().unwrap();
    assert!(all.max > kept.max + 1.0, "{all:?} vs {kept:?}");
    let (_, hi) = sampled(&view, rect, 100).unwrap();
    assert!(hi <= kept.max, "the shared edge s = 2 still counts");
    let only_trimmed = ParamRect {
        s: [2.2, 2.8],
        t: [0.2, 0.8],
    };
    assert_eq!(
        view.range_over_params(only_trimmed, BoundOptions::default())
            .unwrap(),
        None
    );
}

#[test]
fn frame_rectangles_cover_their_parameter_image() {
    let sur = random_surrogate(6, 6, [0.5, 0.5, -1.0], 12);
    let view = SideView::new(&sur, Side::Upper).unwrap();
    let (u0, v0) = sur.domain.frame_uv(1.25, 0.5);
    let (u1, v1) = sur.domain.frame_uv(3.5, 2.75);
    let by_uv = view
        .range_over_uv(
            UvRect {
                u: [u1, u0],
                v: [v0, v1],
            },
            ALL_CELLS,
        )
        .unwrap()
        .unwrap();
    let (lo, hi) = sampled(
        &view,
        ParamRect {
            s: [1.25, 3.5],
            t: [0.5, 2.75],
        },
        60,
    )
    .unwrap();
    assert!(by_uv.min <= lo && hi <= by_uv.max);
}

#[test]
fn bad_requests_are_errors() {
    let sur = random_surrogate(4, 4, [0.0, 0.0, -1.0], 1);
    let view = SideView::new(&sur, Side::Upper).unwrap();
    let rect = ParamRect {
        s: [0.0, 1.0],
        t: [0.0, f64::NAN],
    };
    assert!(matches!(
        view.range_over_params(rect, ALL_CELLS),
        Err(QueryError::NonFiniteRect(..))
    ));
    let deep = BoundOptions {
        cells: CellFilter::All,
        refine: MAX_REFINE + 1,
    };
    let ok = ParamRect {
        s: [0.0, 1.0],
        t: [0.0, 1.0],
    };
    assert!(matches!(
        view.range_over_params(ok, deep),
        Err(QueryError::RefineTooDeep { .. })
    ));
}
