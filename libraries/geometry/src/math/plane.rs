//! Distance in a plane from a point to a segment, shared by the blender's
//! polygons and the guard's unseen-space search.

use glam::DVec2;

/// Distance from `q` to the segment `a b` (a point when they are equal).
pub fn segment_distance(q: DVec2, a: DVec2, b: DVec2) -> f64 {
    let e = b - a;
    let len2 = e.length_squared();
    let t = if len2 > 0.0 {
        ((q - a).dot(e) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    q.distance(a + e * t)
}
