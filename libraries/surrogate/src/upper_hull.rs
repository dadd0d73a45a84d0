//! Upper convex hull of points sorted by abscissa (Andrew's monotone chain).

/// Vertices of the upper hull of `points`, which must be sorted by `.0`.
/// Collinear middle points are dropped; equal abscissae keep the highest point.
pub fn upper_hull(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut hull: Vec<(f64, f64)> = Vec::with_capacity(points.len().min(16));
    upper_hull_into(points, &mut hull);
    hull
}

/// [`upper_hull`] into a reused buffer (cleared first).
pub fn upper_hull_into(points: &[(f64, f64)], hull: &mut Vec<(f64, f64)>) {
    hull.clear();
    for &p in points {
        if let Some(last) = hull.last_mut() {
            if last.0 == p.0 {
                if p.1 > last.1 {
                    *last = p;
                    pop_concave(hull);
                }
                continue;
            }
        }
        while hull.len() >= 2 && !turns_right(hull[hull.len() - 2], hull[hull.len() - 1], p) {
            hull.pop();
        }
        hull.push(p);
    }
}

fn pop_concave(hull: &mut Vec<(f64, f64)>) {
    while hull.len() >= 3 {
        let k = hull.len();
        if turns_right(hull[k - 3], hull[k - 2], hull[k - 1]) {
            break;
        }
        hull.remove(k - 2);
    }
}

/// True when `a -> b -> c` is a strict clockwise (right) turn, i.e. `b` is above
/// the chord `a c` and must stay on the upper hull.
#[inline]
fn turns_right(a: (f64, f64), b: (f64, f64), c: (f64, f64)) -> bool {
    (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0) < 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hull_of_a_cap() {
        let pts = [
            (0.0, 0.0),
            (0.25, 0.5),
            (0.5, 0.2),
            (0.5, 0.9),
            (0.75, 0.5),
            (1.0, 0.0),
        ];
        assert_eq!(
            upper_hull(&pts),
            vec![(0.0, 0.0), (0.25, 0.5), (0.5, 0.9), (0.75, 0.5), (1.0, 0.0)]
        );
        let line = [(0.0, 0.0), (0.5, 0.5), (1.0, 1.0)];
        assert_eq!(upper_hull(&line), vec![(0.0, 0.0), (1.0, 1.0)]);
        assert_eq!(upper_hull(&[(2.0, 1.0)]), vec![(2.0, 1.0)]);
    }

    #[test]
    fn every_point_is_below_the_hull() {
        let mut pts: Vec<(f64, f64)> = (0..200)
            .map(|i| {
                let x = ((i * 7919) % 200) as f64 / 200.0;
                (x, ((i * 104729) % 97) as f64 / 97.0 - x * x)
            })
            .collect();
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        let hull = upper_hull(&pts);
        for &(x, y) in &pts {
            let k = hull.partition_point(|h| h.0 <= x).clamp(1, hull.len() - 1);
            let (a, b) = (hull[k - 1], hull[k]);
            let line = a.1 + (b.1 - a.1) * (x - a.0) / (b.0 - a.0);
            assert!(y <= line + 1e-12);
        }
    }
}
