//! The parameter domain of a cloud: the bounding rectangle of its projection onto
//! the frame's `(u, v)` plane, mapped onto the spline's `[0, cols-1] x [0, rows-1]`.

use super::error::FitError;
use super::model::Domain;
use glam::DVec3;
use rayon::prelude::*;
use shroud_geometry::cloud::CloudError;
use shroud_geometry::math::Frame;

/// Points per lane group: the bounds are kept in this many independent lanes so
/// that the loop vectorises (a single running minimum is one long dependency).
const LANES: usize = 4;

/// Bounds of `(u, v)` over a set of points, and whether every coordinate was finite.
#[derive(Clone, Copy)]
struct Bounds {
    lo: [f64; 2],
    hi: [f64; 2],
    finite: bool,
}

impl Bounds {
    fn merge(self, o: Bounds) -> Bounds {
        Bounds {
            lo: [self.lo[0].min(o.lo[0]), self.lo[1].min(o.lo[1])],
            hi: [self.hi[0].max(o.hi[0]), self.hi[1].max(o.hi[1])],
            finite: self.finite && o.finite,
        }
    }
}

/// Validates the cloud (non-empty, finite) and computes its domain, in one pass.
pub fn domain_of_cloud(
    points: &[[f32; 3]],
    frame: &Frame,
    cols: usize,
    rows: usize,
) -> Result<Domain, FitError> {
    if points.is_empty() {
        return Err(CloudError::Empty.into());
    }
    // Minima and maxima do not depend on the split, so one part per thread will do.
    let part_len = points
        .len()
        .div_ceil(2 * rayon::current_num_threads().max(1))
        .max(1024);
    let axes = world_axes(frame);
    let b = points
        .par_chunks(part_len)
        .map(|pts| match axes {
            Some(axes) => bounds_along_axes(pts, axes),
            None => bounds_of(pts, frame),
        })
        .reduce_with(Bounds::merge)
        .ok_or(CloudError::Empty)?;
    if !b.finite {
        return Err(first_non_finite(points).into());
    }
    let (eu, ev) = (b.hi[0] - b.lo[0], b.hi[1] - b.lo[1]);
    let scale = b.lo.iter().chain(&b.hi).fold(0.0f64, |m, x| m.max(x.abs()));
    // Below this the parameter map would amplify f32 input rounding into noise.
    let floor = scale * 1e-9 + f64::MIN_POSITIVE;
    if eu <= floor || ev <= floor {
        return Err(FitError::Degenerate {
            extent_u: eu,
            extent_v: ev,
        });
    }
    // `+ 0.0` turns a -0.0 minimum into +0.0: which zero a min over {-0.0, +0.0}
    // returns may depend on how the parts were split.
    Ok(Domain {
        u_min: b.lo[0] + 0.0,
        v_min: b.lo[1] + 0.0,
        u_step: eu / (cols - 1) as f64,
        v_step: ev / (rows - 1) as f64,
        cols,
        rows,
    })
}

/// Bounds of `frame.to_local(p)` (same products, same order as `Locator`, hence the
/// same bits). A non-finite coordinate makes `u` (NaN or infinite; f32 input
/// cannot overflow f64) and so the probe `sum(u * 0)` NaN; the bounds are then
/// not used.
fn bounds_of(points: &[[f32; 3]], frame: &Frame) -> Bounds {
    let (fu, fv) = (frame.u, frame.v);
    let mut lo = [[f64::INFINITY; LANES]; 2];
    let mut hi = [[f64::NEG_INFINITY; LANES]; 2];
    let mut probe = [0.0f64; LANES];
    let groups = points.chunks_exact(LANES);
    let rest = groups.remainder();
    for group in groups {
        // One lane per point of the group, each step over all lanes at once.
        let coordinate = |c: usize| -> [f64; LANES] { std::array::from_fn(|l| group[l][c] as f64) };
        let (x, y, z) = (coordinate(0), coordinate(1), coordinate(2));
        let a: [f64; LANES] =
            std::array::from_fn(|l| (x[l] * fu.x) + (y[l] * fu.y) + (z[l] * fu.z));
        let b: [f64; LANES] =
            std::array::from_fn(|l| (x[l] * fv.x) + (y[l] * fv.y) + (z[l] * fv.z));
        for l in 0..LANES {
            probe[l] += a[l] * 0.0;
            // Comparisons rather than `min`/`max`: single vector instructions
            // (the NaN handling is moot, see above).
            lo[0][l] = if a[l] < lo[0][l] { a[l] } else { lo[0][l] };
            hi[0][l] = if a[l] > hi[0][l] { a[l] } else { hi[0][l] };
            lo[1][l] = if b[l] < lo[1][l] { b[l] } else { lo[1][l] };
            hi[1][l] = if b[l] > hi[1][l] { b[l] } else { hi[1][l] };
        }
    }
    for p in rest {
        let (x, y, z) = (p[0] as f64, p[1] as f64, p[2] as f64);
        let a = (x * fu.x) + (y * fu.y) + (z * fu.z);
        let b = (x * fv.x) + (y * fv.y) + (z * fv.z);
        probe[0] += a * 0.0;
        (lo[0][0], hi[0][0]) = (lo[0][0].min(a), hi[0][0].max(a));
        (lo[1][0], hi[1][0]) = (lo[1][0].min(b), hi[1][0].max(b));
    }
    let fold = |v: &[f64; LANES], f: fn(f64, f64) -> f64| v[1..].iter().fold(v[0], |m, &x| f(m, x));
    Bounds {
        lo: [fold(&lo[0], f64::min), fold(&lo[1], f64::min)],
        hi: [fold(&hi[0], f64::max), fold(&hi[1], f64::max)],
        finite: probe.iter().all(|&p| p == 0.0),
    }
}

/// A frame axis that is a world axis: the coordinate it picks and its sign.
type WorldAxis = (usize, f32);

/// The world axes the frame's `u` and `v` are, if both are (as for the default
/// direction, straight down).
fn world_axes(frame: &Frame) -> Option<[WorldAxis; 2]> {
    let world_axis = |axis: DVec3| -> Option<WorldAxis> {
        let c = axis.to_array();
        let mut nonzero = (0..3).filter(|&i| c[i] != 0.0);
        match (nonzero.next(), nonzero.next()) {
            (Some(i), None) if c[i].abs() == 1.0 => Some((i, c[i] as f32)),
            _ => None,
        }
    };
    Some([world_axis(frame.u)?, world_axis(frame.v)?])
}

/// [`bounds_of`] for a frame whose `u` and `v` are world axes: there
/// `x u.x + y u.y + z u.z` is exactly `±` one coordinate (the other products
/// are zeros), so the bounds are those of the coordinates themselves, found in
/// f32 (eight lanes to a vector instead of four) and then widened; only the
/// sign of a zero bound can differ, which [`domain_of_cloud`] normalises.
fn bounds_along_axes(points: &[[f32; 3]], axes: [WorldAxis; 2]) -> Bounds {
    const WIDE: usize = 8;
    // All three coordinates, so that every index is known when compiling.
    let mut lo = [[f32::INFINITY; WIDE]; 3];
    let mut hi = [[f32::NEG_INFINITY; WIDE]; 3];
    let mut probe = [0.0f32; WIDE];
    let mut offer = |l: usize, p: &[f32; 3]| {
        // Infinite or NaN anywhere makes the probe NaN for good.
        probe[l] += (p[0] * 0.0 + p[1] * 0.0) + p[2] * 0.0;
        for c in 0..3 {
            lo[c][l] = if p[c] < lo[c][l] { p[c] } else { lo[c][l] };
            hi[c][l] = if p[c] > hi[c][l] { p[c] } else { hi[c][l] };
        }
    };
    let groups = points.chunks_exact(WIDE);
    let rest = groups.remainder();
    for group in groups {
        group.iter().enumerate().for_each(|(l, p)| offer(l, p));
    }
    rest.iter().for_each(|p| offer(0, p));
    let fold = |v: &[f32; WIDE], f: fn(f32, f32) -> f32| v[1..].iter().fold(v[0], |m, &x| f(m, x));
    let bound = |(c, sign): WorldAxis| -> (f64, f64) {
        let (low, high) = (fold(&lo[c], f32::min) as f64, fold(&hi[c], f32::max) as f64);
        if sign > 0.0 {
            (low, high)
        } else {
            (-high, -low)
        }
    };
    let (u, v) = (bound(axes[0]), bound(axes[1]));
    Bounds {
        lo: [u.0, v.0],
        hi: [u.1, v.1],
        finite: probe.iter().all(|&p| p == 0.0),
    }
}

/// The error naming the first non-finite point (the cloud is known to have one).
#[cold]
fn first_non_finite(points: &[[f32; 3]]) -> CloudError {
    let (index, &[x, y, z]) = points
        .iter()
        .enumerate()
        .find(|(_, p)| !p.iter().all(|c| c.is_finite()))
        .unwrap_or((0, &points[0]));
    CloudError::NonFinite { index, x, y, z }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_match_the_frame_coordinates_of_every_point() {
        let frame = Frame::from_direction(DVec3::new(0.4, -0.3, -1.0)).unwrap();
        let points: Vec<[f32; 3]> = (0..1001)
            .map(|i| {
                let a = i as f32 * 0.173;
                [a.sin() * 3.0, a.cos() * 2.0 + 0.5, (a * 0.7).sin()]
            })
            .collect();
        let domain = domain_of_cloud(&points, &frame, 11, 7).unwrap();
        let local: Vec<DVec3> = points
            .iter()
            .map(|p| frame.to_local(DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64)))
            .collect();
        let u_min = local.iter().map(|l| l.x).fold(f64::INFINITY, f64::min);
        let u_max = local.iter().map(|l| l.x).fold(f64::NEG_INFINITY, f64::max);
        let v_min = local.iter().map(|l| l.y).fold(f64::INFINITY, f64::min);
        assert_eq!((domain.u_min, domain.v_min), (u_min, v_min));
        assert_eq!(domain.u_step, (u_max - u_min) / 10.0);
    }

    /// Frames whose axes are world axes take the f32 path; their bounds are
    /// the general path's, but for the sign of a zero bound (which the domain
    /// normalises), on clouds with zeros of both signs.
    #[test]
    fn world_axis_frames_give_the_general_domain() {
        let mut points: Vec<[f32; 3]> = (0..5003)
            .map(|i| {
                let a = i as f32 * 0.377;
                [
                    a.sin() * 2.0 - 0.3,
                    a.cos() * 1.5 + 0.2,
                    (a * 0.3).sin() * 0.5,
                ]
            })
            .collect();
        points[17] = [0.0, -0.0, 0.0];
        points[4000] = [-0.0, 0.0, -0.0];
        let directions = [
            [0.0, 0.0, -1.0],
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, -3.0, 0.0],
        ];
        for d in directions {
            let frame = Frame::from_direction(DVec3::from_array(d)).unwrap();
            let axes = world_axes(&frame).expect("a world-axis frame");
            for cloud in [&points[..], &points[..9], &points[17..18]] {
                let (fast, general) = (bounds_along_axes(cloud, axes), bounds_of(cloud, &frame));
                assert!(fast.finite && general.finite);
                for k in 0..2 {
                    assert_eq!(fast.lo[k] + 0.0, general.lo[k] + 0.0, "{d:?} lo {k}");
                    assert_eq!(fast.hi[k], general.hi[k], "{d:?} hi {k}");
                }
            }
            let mut bad = points.clone();
            bad[4321][2] = f32::NAN;
            assert!(!bounds_along_axes(&bad, axes).finite);
            bad[4321][2] = f32::NEG_INFINITY;
            assert!(!bounds_along_axes(&bad, axes).finite);
        }
        let tilted = Frame::from_direction(DVec3::new(0.0, 0.1, -1.0)).unwrap();
        assert!(world_axes(&tilted).is_none());
    }

    #[test]
    fn the_first_non_finite_point_is_named() {
        let frame = Frame::from_direction(DVec3::new(0.0, 0.0, -1.0)).unwrap();
        let mut points = vec![[1.0f32, 2.0, 3.0]; 5000];
        points[10] = [0.0, 1.0, 2.0];
        points[3001] = [0.0, f32::INFINITY, 0.0];
        points[4002] = [f32::NAN, 0.0, 0.0];
        let err = domain_of_cloud(&points, &frame, 4, 4).unwrap_err();
        assert_eq!(
            err,
            FitError::Cloud(CloudError::NonFinite {
                index: 3001,
                x: 0.0,
                y: f32::INFINITY,
                z: 0.0
            })
        );
        assert!(matches!(
            domain_of_cloud(&[], &frame, 4, 4),
            Err(FitError::Cloud(CloudError::Empty))
        ));
    }
}
