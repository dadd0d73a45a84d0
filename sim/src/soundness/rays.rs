//! Exact ray intersections with the scene's true shapes: the floor square,
//! balls, boxes and capsules, each from its definition (quadratics and slabs
//! in f64), so that a scan is a sample of the true geometry.

use super::solids::{Body, Solid, FLOOR_HALF_WIDTH};
use glam::DVec3;

/// What a ray hit first.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Hit {
    Floor,
    Solid(usize),
}

/// Distance along the unit ray `o + d s` (`s > 0`) to the floor square.
pub fn ray_floor(o: DVec3, d: DVec3) -> Option<f64> {
    if d.z >= 0.0 || o.z <= 0.0 {
        return None;
    }
    let s = -o.z / d.z;
    let p = o + d * s;
    (p.x.abs() <= FLOOR_HALF_WIDTH && p.y.abs() <= FLOOR_HALF_WIDTH).then_some(s)
}

/// First entry of the unit ray into the ball (centre `c`, radius `r`); a ray
/// starting inside reports 0 (it is blocked at once).
fn ray_ball(o: DVec3, d: DVec3, c: DVec3, r: f64) -> Option<f64> {
    let m = o - c;
    let b = m.dot(d);
    let cc = m.length_squared() - r * r;
    if cc <= 0.0 {
        return Some(0.0);
    }
    if b >= 0.0 {
        return None;
    }
    let disc = b * b - cc;
    if disc < 0.0 {
        return None;
    }
    Some(-b - disc.sqrt())
}

/// Slab test in the box's own frame (`o`, `d` already local).
fn ray_local_box(o: DVec3, d: DVec3, half: DVec3) -> Option<f64> {
    let (mut near, mut far) = (0.0f64, f64::INFINITY);
    for k in 0..3 {
        let (ok, dk, hk) = (o[k], d[k], half[k]);
        if dk == 0.0 {
            if ok.abs() > hk {
                return None;
            }
            continue;
        }
        let (a, b) = ((-hk - ok) / dk, (hk - ok) / dk);
        near = near.max(a.min(b));
        far = far.min(a.max(b));
        if near > far {
            return None;
        }
    }
    Some(near)
}

/// First entry into the capsule: the lateral surface of its cylinder within
/// the segment, or either end ball, whichever comes first.
fn ray_capsule(o: DVec3, d: DVec3, c: DVec3, axis: DVec3, half: f64, r: f64) -> Option<f64> {
    let (a, b) = (c - axis * half, c + axis * half);
    let mut best = [ray_ball(o, d, a, r), ray_ball(o, d, b, r)]
        .into_iter()
        .flatten()
        .fold(f64::INFINITY, f64::min);
    // The cylinder: |(m + d s) - axis (axis . (m + d s))| = r.
    let m = o - c;
    let (dp, mp) = (d - axis * d.dot(axis), m - axis * m.dot(axis));
    let qa = dp.length_squared();
    let qb = mp.dot(dp);
    let qc = mp.length_squared() - r * r;
    if qc <= 0.0 && m.dot(axis).abs() <= half {
        return Some(0.0);
    }
    if qa > 0.0 {
        let disc = qb * qb - qa * qc;
        if disc >= 0.0 {
            let s = (-qb - disc.sqrt()) / qa;
            if s >= 0.0 && (m + d * s).dot(axis).abs() <= half {
                best = best.min(s);
            }
        }
    }
    best.is_finite().then_some(best)
}

/// Distance along the unit ray to `solid` at time `t` (0 from inside).
pub fn ray_solid(o: DVec3, d: DVec3, solid: &Solid, t: f64) -> Option<f64> {
    let c = solid.centre_at(t);
    match solid.body {
        Body::Sphere { radius } => ray_ball(o, d, c, radius),
        Body::Cuboid { half, rotation } => {
            let inv = rotation.inverse();
            ray_local_box(inv * (o - c), inv * d, half)
        }
        Body::Capsule {
            half_length,
            axis,
            radius,
        } => ray_capsule(o, d, c, axis, half_length, radius),
    }
}

/// The first thing the unit ray meets at time `t`, and how far along.
pub fn cast(o: DVec3, d: DVec3, solids: &[Solid], t: f64) -> Option<(f64, Hit)> {
    let mut best = ray_floor(o, d).map(|s| (s, Hit::Floor));
    for (i, solid) in solids.iter().enumerate() {
        if let Some(s) = ray_solid(o, d, solid, t) {
            if best.is_none_or(|(b, _)| s < b) {
                best = Some((s, Hit::Solid(i)));
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DQuat;

    fn at(body: Body, centre: DVec3) -> Solid {
        Solid {
            body,
            centre,
            velocity: DVec3::ZERO,
            black: false,
        }
    }

    #[test]
    fn hits_land_on_the_surface() {
        let o = DVec3::new(0.1, -0.2, 3.0);
        let solids = [
            at(Body::Sphere { radius: 0.3 }, DVec3::new(0.0, 0.0, 0.3)),
            at(
                Body::Cuboid {
                    half: DVec3::new(0.2, 0.3, 0.1),
                    rotation: DQuat::from_rotation_z(0.7) * DQuat::from_rotation_x(0.3),
                },
                DVec3::new(1.0, 0.5, 0.4),
            ),
            at(
                Body::Capsule {
                    half_length: 0.4,
                    axis: DVec3::new(1.0, 1.0, 0.0).normalize(),
                    radius: 0.1,
                },
                DVec3::new(-1.0, 0.5, 0.1),
            ),
        ];
        let mut hits = [0usize; 4];
        for i in 0..60 {
            for j in 0..60 {
                let d =
                    DVec3::new(-1.0 + i as f64 / 30.0, -1.0 + j as f64 / 30.0, -1.5).normalize();
                let Some((s, hit)) = cast(o, d, &solids, 0.0) else {
                    continue;
                };
                let p = o + d * s;
                let sd = match hit {
                    Hit::Floor => {
                        hits[3] += 1;
                        p.z
                    }
                    Hit::Solid(k) => {
                        hits[k] += 1;
                        solids[k].signed_distance(p, 0.0)
                    }
                };
                assert!(sd.abs() < 1e-9, "hit {hit:?} off the surface by {sd}");
                // Nothing is crossed before the hit.
                for (k, solid) in solids.iter().enumerate() {
                    let before = o + d * (s * 0.999);
                    assert!(
                        solid.signed_distance(before, 0.0) > 0.0,
                        "ray passed solid {k}"
                    );
                }
            }
        }
        assert!(hits.iter().all(|&h| h > 0), "{hits:?}");
    }

    #[test]
    fn misses_and_moving_targets() {
        let ball = Solid {
            body: Body::Sphere { radius: 0.1 },
            centre: DVec3::ZERO,
            velocity: DVec3::new(1.0, 0.0, 0.0),
            black: false,
        };
        let o = DVec3::new(1.0, 0.0, 2.0);
        assert_eq!(ray_solid(o, -DVec3::Z, &ball, 0.0), None);
        let s = ray_solid(o, -DVec3::Z, &ball, 1.0).expect("the ball moved under the ray");
        assert!((s - 1.9).abs() < 1e-12);
        assert_eq!(ray_floor(o, DVec3::Z), None);
        assert_eq!(
            ray_floor(
                DVec3::new(0.0, 0.0, 1.0),
                DVec3::new(1.0, 0.0, -1e-3).normalize()
            ),
            None
        );
    }
}
