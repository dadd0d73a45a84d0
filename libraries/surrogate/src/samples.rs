//! Small fitted surrogates for tests: this crate's validation tests and the
//! file-format tests of `shroud-shapes` (public, and hidden from the docs, only
//! for those).

use crate::{fit_surrogate, FitOptions, Sides, Surrogate};

/// A wavy height field on a 6 x 4.5 grid with the corner `x + y > 6.5` missing, so
/// that trimming removes whole cells and single triangles.
pub fn wavy_cloud() -> Vec<[f32; 3]> {
    let mut points = Vec::new();
    for i in 0..60 {
        for j in 0..45 {
            let (x, y) = (i as f32 * 0.1, j as f32 * 0.1);
            if x + y > 6.5 {
                continue;
            }
            let jitter = ((i * 7919 + j * 104_729) % 97) as f32 / 97.0 - 0.5;
            points.push([
                x,
                y,
                (1.3 * x).sin() + 0.4 * (2.0 * y).cos() + 0.05 * jitter,
            ]);
        }
    }
    points
}

/// A 6 x 5 surrogate of [`wavy_cloud`] seen along a slightly tilted direction.
pub fn fitted(sides: Sides, trim: bool) -> Surrogate {
    let options = FitOptions {
        cols: 6,
        rows: 5,
        sides,
        trim,
        direction: [0.1, -0.05, -1.0],
        ..Default::default()
    };
    fit_surrogate(&wavy_cloud(), &options).unwrap()
}
