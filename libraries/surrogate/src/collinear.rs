//! Rejects clouds whose projection is a line segment even when the segment is
//! skew to the frame axes (the bounding-box test in `footprint` only sees thin
//! boxes). Such a footprint has no 2D extent for a surface to span.
//!
//! The test is exact and cheap: the extreme points kept by the streaming pass are
//! real points, so if *they* already span a width, the cloud does; only when they
//! are collinear is the whole cloud measured against their line.

use super::error::FitError;
use glam::{DVec2, DVec3};
use rayon::prelude::*;
use shroud_geometry::math::Frame;

/// Relative width below which a footprint counts as a line (as in `footprint`).
const RELATIVE_WIDTH: f64 = 1e-9;

/// Extreme points looked at first, at most: any real points that span a width
/// prove the cloud does, and a few thousand spread over the grid settle almost
/// every cloud (the rest is measured in full).
const SAMPLE: usize = 2048;

/// `Err(Collinear)` when every point lies within a negligible width of one line.
pub fn ensure_not_collinear(
    points: &[[f32; 3]],
    frame: &Frame,
    candidates: &[u32],
) -> Result<(), FitError> {
    let uv = |i: usize| {
        let p = points[i];
        let l = frame.to_local(DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64));
        DVec2::new(l.x, l.y)
    };
    let stride = candidates.len().div_ceil(SAMPLE).max(1);
    let sample: Vec<DVec2> = candidates
        .iter()
        .step_by(stride)
        .map(|&i| uv(i as usize))
        .collect();
    let Some(line) = principal_line(&sample) else {
        return Err(FitError::Collinear {
            width: 0.0,
            length: 0.0,
        });
    };
    let scale = sample.iter().fold(line.origin.abs().max_element(), |m, p| {
        m.max(p.abs().max_element())
    });
    let floor = RELATIVE_WIDTH * scale.max(line.length) + f64::MIN_POSITIVE;
    if line.width_of(&sample) > floor {
        return Ok(());
    }
    let width = (0..points.len())
        .into_par_iter()
        .map(|i| line.distance(uv(i)))
        .reduce(|| 0.0, f64::max);
    if width > floor {
        Ok(())
    } else {
        Err(FitError::Collinear {
            width,
            length: line.length,
        })
    }
}

/// The line through a point set's mean along its principal direction.
struct Line {
    origin: DVec2,
    normal: DVec2,
    length: f64,
}

impl Line {
    fn distance(&self, p: DVec2) -> f64 {
        (p - self.origin).dot(self.normal).abs()
    }

    fn width_of(&self, points: &[DVec2]) -> f64 {
        points.iter().map(|&p| self.distance(p)).fold(0.0, f64::max)
    }
}

/// `None` when all points coincide.
fn principal_line(points: &[DVec2]) -> Option<Line> {
    let n = points.len() as f64;
    let mean = points.iter().fold(DVec2::ZERO, |a, &p| a + p) / n;
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    for p in points {
        let d = *p - mean;
        sxx += d.x * d.x;
        sxy += d.x * d.y;
        syy += d.y * d.y;
    }
    // Direction of the larger eigenvalue of [[sxx, sxy], [sxy, syy]].
    let angle = 0.5 * (2.0 * sxy).atan2(sxx - syy);
    let direction = DVec2::new(angle.cos(), angle.sin());
    let along = points.iter().map(|&p| (p - mean).dot(direction));
    let (lo, hi) = along.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
        (a.min(x), b.max(x))
    });
    let length = hi - lo;
    (length > 0.0).then_some(Line {
        origin: mean,
        normal: direction.perp(),
        length,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame() -> Frame {
        Frame::from_direction(DVec3::new(0.0, 0.0, -1.0)).unwrap()
    }

    /// More extreme points than the sample holds: a line is still a line, and
    /// one point off it that the sample skips is found by the full pass.
    #[test]
    fn a_sampled_line_is_collinear_unless_a_skipped_point_leaves_it() {
        let mut line: Vec<[f32; 3]> = (0..10_000)
            .map(|i| [0.001 * i as f32, 0.002 * i as f32, (i as f32).cos()])
            .collect();
        let all: Vec<u32> = (0..line.len() as u32).collect();
        assert!(matches!(
            ensure_not_collinear(&line, &frame(), &all),
            Err(FitError::Collinear { .. })
        ));
        // Index 1 is not among every fifth candidate the sample takes.
        line[1] = [0.5, -0.5, 0.0];
        assert!(ensure_not_collinear(&line, &frame(), &all).is_ok());
    }

    #[test]
    fn a_skew_line_is_collinear_and_a_thin_triangle_is_not() {
        let line: Vec<[f32; 3]> = (0..40)
            .map(|i| [0.25 * i as f32, 0.25 * i as f32, (i as f32).sin()])
            .collect();
        let all: Vec<u32> = (0..40).collect();
        assert!(matches!(
            ensure_not_collinear(&line, &frame(), &all[..3]),
            Err(FitError::Collinear { .. })
        ));
        let mut bent = line.clone();
        bent[17][1] += 0.01;
        // The candidates alone are collinear; the full pass finds the bent point.
        assert!(ensure_not_collinear(&bent, &frame(), &[0, 39]).is_ok());
        assert!(ensure_not_collinear(&bent, &frame(), &all).is_ok());
    }
}
