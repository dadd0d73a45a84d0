//! Parts to paste onto a scene (the blender's children, paper 001): analytic open
//! surfaces whose only boundary loop lies in z = 0, their body above it.

use crate::SceneError;
use std::f64::consts::{PI, TAU};

/// Deterministic uniform numbers in [0, 1) (SplitMix64).
pub struct Jitter(u64);

impl Jitter {
    pub fn new(seed: u64) -> Self {
        Self(seed ^ 0x9e37_79b9_7f4a_7c15)
    }
    pub fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn f32s(x: f64, y: f64, z: f64) -> [f32; 3] {
    [x as f32, y as f32, z as f32]
}

/// Upper hemisphere of radius `r` centred at the origin (open rim at z = 0),
/// Fibonacci-spaced, `count` points.
pub fn hemisphere(r: f64, count: usize) -> Vec<[f32; 3]> {
    let golden = PI * (3.0 - 5f64.sqrt());
    (0..count)
        .map(|i| {
            let z = 1.0 - (i as f64 + 0.5) / count as f64; // (0, 1]
            let s = (1.0 - z * z).sqrt();
            let t = golden * i as f64;
            f32s(r * s * t.cos(), r * s * t.sin(), r * z)
        })
        .collect()
}

/// Upper half of a cylinder of radius `r` along x, length `len`, centred at the
/// origin, with its two ends closed by half discs: the only open boundary is the
/// rectangle in z = 0. About `count` points, uniform by area.
pub fn half_cylinder(r: f64, len: f64, count: usize, seed: u64) -> Vec<[f32; 3]> {
    let shell = PI * r * len;
    let caps = PI * r * r; // two half discs
    let n_shell = (count as f64 * shell / (shell + caps)) as usize;
    let mut rng = Jitter::new(seed);
    let mut out = Vec::with_capacity(count);
    let rows = ((n_shell as f64) * len / (PI * r)).sqrt().ceil() as usize;
    let cols = (n_shell / rows.max(1)).max(1);
    for i in 0..rows {
        for j in 0..cols {
            let x = -0.5 * len + (i as f64 + 0.5 + 0.4 * (rng.uniform() - 0.5)) * len / rows as f64;
            let a = (j as f64 + 0.5 + 0.4 * (rng.uniform() - 0.5)) * PI / cols as f64;
            out.push(f32s(x, r * a.cos(), r * a.sin()));
        }
    }
    let per_cap = (count - out.len().min(count)) / 2;
    for end in [-0.5 * len, 0.5 * len] {
        let golden = PI * (3.0 - 5f64.sqrt());
        for i in 0..per_cap {
            // Fibonacci half disc (y, z >= 0.02 r so the rim stays the rectangle's).
            let rad = r * ((i as f64 + 0.5) / per_cap as f64).sqrt();
            let t = (golden * i as f64).rem_euclid(TAU);
            let (y, z) = (rad * t.cos(), rad * t.sin().abs());
            if z > 0.02 * r {
                out.push(f32s(end, y, z));
            }
        }
    }
    out
}

/// The parts [`part_by_name`] knows.
pub const PART_NAMES: [&str; 2] = ["hemisphere", "half-cylinder"];

/// A part by name, for command lines: `hemisphere` of radius `size`, or
/// `half-cylinder` of radius `size` and length `4 size`; about `count` points.
pub fn part_by_name(name: &str, size: f64, count: usize) -> Result<Vec<[f32; 3]>, SceneError> {
    if !size.is_finite() {
        return Err(SceneError::NonFinite {
            parameter: "size".into(),
            value: size,
        });
    }
    if size <= 0.0 {
        return Err(SceneError::NotPositive {
            parameter: "size".into(),
            value: size,
        });
    }
    crate::error::check_points("points", count)?;
    match name {
        "hemisphere" => Ok(hemisphere(size, count)),
        "half-cylinder" => Ok(half_cylinder(size, 4.0 * size, count, 5)),
        _ => Err(SceneError::UnknownPart {
            name: name.to_owned(),
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parts_are_open_above_the_plane_and_named() {
        for name in PART_NAMES {
            let pts = part_by_name(name, 0.5, 2_000).unwrap();
            assert!(pts.len() > 1_500, "{name}: {}", pts.len());
            assert!(pts
                .iter()
                .all(|p| p[2] >= 0.0 && p.iter().all(|v| v.is_finite())));
        }
        assert!(matches!(
            part_by_name("teapot", 1.0, 10),
            Err(SceneError::UnknownPart { .. })
        ));
        assert!(part_by_name("hemisphere", f64::NAN, 10).is_err());
        assert!(part_by_name("hemisphere", -1.0, 10).is_err());
        assert!(part_by_name("hemisphere", 1.0, 0).is_err());
    }
}
