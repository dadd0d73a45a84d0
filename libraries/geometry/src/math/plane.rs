//! Distance in a plane from a point to a segment, shared by the blender's
//! polygons and the guard's unseen-space search.

use glam::DVec2;

/// Distance from `q` to the segment `a b` (a point when they are equal).
pub fn segment_distance(q: DVec2, a: DVec2, b: DVec2) -> f64 {
    segment_distance_squared(q, a, b).sqrt()
}

/// Square of [`segment_distance`], the same bits up to its final square root
/// (searches compare squares and take one root at the end).
pub fn segment_distance_squared(q: DVec2, a: DVec2, b: DVec2) -> f64 {
    let e = b - a;
    let len2 = e.length_squared();
    let t = if len2 > 0.0 {
        ((q - a).dot(e) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (q - (a + e * t)).length_squared()
}
