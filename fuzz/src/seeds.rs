//! Helpers that build seed inputs shared by several targets.

/// A stream seed: the chunking byte [`crate::check::stream`] reads, then `bytes`.
pub fn stream(chunking: u8, bytes: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(bytes.len() + 1);
    out.push(chunking);
    out.extend_from_slice(bytes);
    out
}

use shroud_surrogate::{fit_surrogate, FitOptions, Sides, Surrogate};

/// A small surrogate with both sides and a trim mask, fitted to a wavy
/// height field with a missing corner (so that trimming removes cells).
pub fn surrogate() -> Surrogate {
    let mut points = Vec::new();
    for i in 0..30u16 {
        for j in 0..20u16 {
            let (x, y) = (f32::from(i) * 0.2, f32::from(j) * 0.2);
            if x + y < 6.0 {
                points.push([x, y, (1.3 * x).sin() + 0.4 * (2.0 * y).cos()]);
            }
        }
    }
    let options = FitOptions {
        cols: 5,
        rows: 4,
        sides: Sides::Sandwich,
        trim: true,
        ..Default::default()
    };
    fit_surrogate(&points, &options).expect("the seed cloud fits")
}
