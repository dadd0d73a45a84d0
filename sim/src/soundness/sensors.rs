//! Range sensors of a soundness scene: a pose, a field of view (a cone or a
//! rectangular frustum), a maximum range and a square grid of rays on the
//! image plane; a scan at the sensor's own time, and whether it saw a point.

use super::rays::{cast, Hit};
use super::solids::Solid;
use glam::DVec3;
use kiddo::{ImmutableKdTree, SquaredEuclidean};
use shroud_geometry::cloud::{dark_cones, EmptyRays};
use shroud_msg as message;

/// The rays a sensor casts, as bounds on the image plane at unit distance
/// (tangents of the half angles).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FieldOfView {
    /// Every ray within `half_angle` (radians) of the look direction.
    Cone { half_angle: f64 },
    /// Rays within `half_x` to the right and left and `half_y` up and down.
    Frustum { half_x: f64, half_y: f64 },
}

impl FieldOfView {
    /// Whether the image-plane point `(x, y)` (at unit distance) is in view.
    fn contains(&self, x: f64, y: f64) -> bool {
        match *self {
            FieldOfView::Cone { half_angle } => {
                let t = half_angle.tan();
                x * x + y * y <= t * t
            }
            FieldOfView::Frustum { half_x, half_y } => {
                x.abs() <= half_x.tan() && y.abs() <= half_y.tan()
            }
        }
    }

    /// Half extents of the image-plane rectangle holding the view.
    fn extent(&self) -> (f64, f64) {
        match *self {
            FieldOfView::Cone { half_angle } => (half_angle.tan(), half_angle.tan()),
            FieldOfView::Frustum { half_x, half_y } => (half_x.tan(), half_y.tan()),
        }
    }

    /// Area of the view on the image plane (to size the ray grid).
    pub fn image_area(&self) -> f64 {
        let (x, y) = self.extent();
        match self {
            FieldOfView::Cone { .. } => std::f64::consts::PI * x * x,
            FieldOfView::Frustum { .. } => 4.0 * x * y,
        }
    }
}

/// One scan: the points, and per ray of the image grid (row-major,
/// `columns` a row) whether it was cast and returned nothing.
#[derive(Debug, Clone, PartialEq)]
pub struct Scan {
    pub points: Vec<[f32; 3]>,
    pub columns: usize,
    pub empty: Vec<bool>,
}

/// A scan's rays that returned nothing ([`Sensor::empty_rays`]), with
/// kiddo's kd-tree over them.
pub struct EmptyRayIndex {
    rays: Vec<DVec3>,
    tree: Option<ImmutableKdTree<f64, 3>>,
}

impl EmptyRayIndex {
    /// The stored vector nearest `q` (`None` when no ray was empty).
    fn nearest(&self, q: DVec3) -> Option<DVec3> {
        let tree = self.tree.as_ref()?;
        let n = tree.nearest_one::<SquaredEuclidean>(&q.to_array());
        Some(self.rays[n.item as usize])
    }
}

/// How a sensor's rays leave it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Projection {
    /// From the origin, through the image plane (a camera, a lidar).
    Perspective,
    /// Parallel to the look direction, from an aperture plane through the
    /// origin, spaced as the perspective rays are at `reference` distance:
    /// the sensor the guard's views assume (every column along the look
    /// direction over the footprint is seen from outside the scene).
    Parallel { reference: f64 },
}

/// A range sensor and when it scans.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sensor {
    pub origin: DVec3,
    /// Unit look direction (also the fitted view's direction).
    pub look: DVec3,
    /// Unit image axes, orthogonal to `look` and to each other.
    pub right: DVec3,
    pub up: DVec3,
    pub fov: FieldOfView,
    pub max_range: f64,
    /// Spacing of the ray grid on the image plane at unit distance.
    pub step: f64,
    /// Scan time, seconds on the scene clock.
    pub time: f64,
    pub projection: Projection,
}

impl Sensor {
    /// One line for replay logs: pose, aperture, range, ray grid and
    /// projection.
    pub fn describe(&self) -> String {
        format!(
            "origin {:.3?} look {:.3?} {:?} range {:.2} step {:.5} ({} rays, margin {:.3}) {:?}",
            self.origin.to_array(),
            self.look.to_array(),
            self.fov,
            self.max_range,
            self.step,
            self.ray_count(),
            self.sampling_margin(),
            self.projection,
        )
    }

    /// A sensor at `origin` looking along `look` (need not be unit), its
    /// image x axis as horizontal as the look allows.
    pub fn new(
        origin: DVec3,
        look: DVec3,
        fov: FieldOfView,
        max_range: f64,
        step: f64,
        time: f64,
    ) -> Self {
        let look = look.normalize();
        let helper = if look.x.abs() < 0.9 {
            DVec3::X
        } else {
            DVec3::Y
        };
        let up = look.cross(helper).normalize();
        let right = up.cross(look);
        Self {
            origin,
            look,
            right,
            up,
            fov,
            max_range,
            step,
            time,
            projection: Projection::Perspective,
        }
    }

    /// The ray through image-plane point `(x, y)`: its start and unit
    /// direction.
    fn ray(&self, x: f64, y: f64) -> (DVec3, DVec3) {
        match self.projection {
            Projection::Perspective => (
                self.origin,
                (self.look + self.right * x + self.up * y).normalize(),
            ),
            Projection::Parallel { reference } => (
                self.origin + (self.right * x + self.up * y) * reference,
                self.look,
            ),
        }
    }

    /// Image-plane index range of the grid along one axis.
    fn half_count(extent: f64, step: f64) -> i64 {
        (extent / step).floor() as i64
    }

    /// The number of rays of one scan.
    pub fn ray_count(&self) -> usize {
        let (ex, ey) = self.fov.extent();
        let (nx, ny) = (
            Self::half_count(ex, self.step),
            Self::half_count(ey, self.step),
        );
        let mut n = 0;
        for j in -ny..=ny {
            for i in -nx..=nx {
                n += usize::from(
                    self.fov
                        .contains(i as f64 * self.step, j as f64 * self.step),
                );
            }
        }
        n
    }

    /// Largest distance between neighbouring rays (diagonal neighbours of the
    /// grid) at the maximum range: a tangent-plane step subtends at most
    /// `step` radians (the derivative of atan is at most 1), so the gap is at
    /// most `max_range * step * sqrt(2)`. An object that fits between four
    /// rays can be missed; the guard only promises distance to what was
    /// sampled.
    pub fn sampling_margin(&self) -> f64 {
        let spread = match self.projection {
            Projection::Perspective => self.max_range,
            Projection::Parallel { reference } => reference,
        };
        spread * self.step * std::f64::consts::SQRT_2
    }

    /// One scan at the sensor's time: the first hit of every ray, unless it
    /// is beyond range or on a black solid (which blocks the ray all the
    /// same), and which rays returned nothing.
    pub fn scan(&self, solids: &[Solid]) -> Scan {
        let (ex, ey) = self.fov.extent();
        let (nx, ny) = (
            Self::half_count(ex, self.step),
            Self::half_count(ey, self.step),
        );
        let columns = (2 * nx + 1) as usize;
        let mut scan = Scan {
            points: Vec::new(),
            columns,
            empty: Vec::with_capacity(columns * (2 * ny + 1) as usize),
        };
        for j in -ny..=ny {
            for i in -nx..=nx {
                let (x, y) = (i as f64 * self.step, j as f64 * self.step);
                if !self.fov.contains(x, y) {
                    scan.empty.push(false);
                    continue;
                }
                let (o, d) = self.ray(x, y);
                let hit = cast(o, d, solids, self.time)
                    .filter(|&(s, hit)| {
                        s <= self.max_range && !matches!(hit, Hit::Solid(k) if solids[k].black)
                    })
                    .map(|(s, _)| o + d * s);
                scan.empty.push(hit.is_none());
                if let Some(p) = hit {
                    scan.points.push([p.x as f32, p.y as f32, p.z as f32]);
                }
            }
        }
        scan
    }

    /// The scan's rays that returned nothing, as its driver would state them
    /// in the cloud (`shroud_geometry::cloud::dark_cones`): perspective rays only
    /// (parallel rays have no apex). Neighbouring rays are at most `step
    /// sqrt(2)` apart on the image plane at unit distance, which subtends at
    /// most that angle (the derivative of atan is at most 1).
    pub fn stated_no_return(&self, scan: &Scan) -> Option<message::NoReturn> {
        if self.projection != Projection::Perspective || scan.columns == 0 {
            return None;
        }
        let rays = EmptyRays {
            rows: scan.empty.len() / scan.columns,
            columns: scan.columns,
            empty: &scan.empty,
        };
        let (nx, ny) = ((scan.columns / 2) as f64, (rays.rows / 2) as f64);
        let direction = |k: usize| {
            let (i, j) = (
                (k % scan.columns) as f64 - nx,
                (k / scan.columns) as f64 - ny,
            );
            self.ray(i * self.step, j * self.step).1
        };
        let spread = self.step * std::f64::consts::SQRT_2;
        // A grid this fine never needs cones of 90 degrees: an error here
        // would be a bug of the harness, so the view simply states nothing
        // and the run's findings show it.
        dark_cones(self.origin.to_array(), &rays, direction, spread)
            .ok()
            .flatten()
    }

    /// The scan's rays that returned nothing, for
    /// [`Self::clearance_from_empty_rays`]: their unit directions
    /// (perspective) or their lateral offsets from the origin (parallel).
    pub fn empty_rays(&self, scan: &Scan) -> EmptyRayIndex {
        let rows = scan.empty.len() / scan.columns.max(1);
        let (nx, ny) = ((scan.columns / 2) as f64, (rows / 2) as f64);
        let rays = scan
            .empty
            .iter()
            .enumerate()
            .filter(|(_, &e)| e)
            .map(|(k, _)| {
                let (i, j) = (
                    (k % scan.columns) as f64 - nx,
                    (k / scan.columns) as f64 - ny,
                );
                let (o, d) = self.ray(i * self.step, j * self.step);
                match self.projection {
                    Projection::Perspective => d,
                    Projection::Parallel { .. } => o - self.origin,
                }
            });
        let rays: Vec<DVec3> = rays.collect();
        let coords: Vec<[f64; 3]> = rays.iter().map(|d| d.to_array()).collect();
        EmptyRayIndex {
            tree: (!coords.is_empty()).then(|| ImmutableKdTree::new_from_slice(&coords)),
            rays,
        }
    }

    /// How far `p` lies from every ray that returned nothing (the whole
    /// ray: a black object may stand anywhere along it), less the gap to
    /// the neighbouring rays at `p`'s distance (`step sqrt(2)` radians, or
    /// that times `reference` for parallel rays). Where this exceeds a
    /// reach, every point within that reach is crossed by rays that
    /// returned from beyond it or lies between such rays: space the sensor
    /// proved free. The harness's own geometry: exact point-to-ray
    /// distances to the nearest empty ray (a kd-tree over directions finds
    /// the one at the smallest angle, hence the nearest; over lateral
    /// offsets for parallel rays).
    pub fn clearance_from_empty_rays(&self, p: DVec3, empty: &EmptyRayIndex) -> f64 {
        let to = p - self.origin;
        match self.projection {
            Projection::Perspective => {
                let length = to.length();
                let gap = length * self.step * std::f64::consts::SQRT_2;
                let Some(d) = empty.nearest(to / length.max(1e-300)) else {
                    return f64::INFINITY;
                };
                let along = to.dot(d);
                let off = if along > 0.0 {
                    (to - d * along).length()
                } else {
                    length
                };
                off - gap
            }
            Projection::Parallel { reference } => {
                let lateral = to - self.look * to.dot(self.look);
                let gap = reference * self.step * std::f64::consts::SQRT_2;
                empty
                    .nearest(lateral)
                    .map_or(f64::INFINITY, |d| (d - lateral).length() - gap)
            }
        }
    }

    /// Whether the sensor saw the point `p` as free space at its scan time:
    /// inside its field of view and range, and no solid (nor the floor) on
    /// the line of sight up to it. (Rays are discrete; this is the space the
    /// sensor looked through, not the rays themselves.)
    pub fn sees(&self, p: DVec3, solids: &[Solid]) -> bool {
        if !self.covers(p) {
            return false;
        }
        let (o, to) = match self.projection {
            Projection::Perspective => (self.origin, p - self.origin),
            Projection::Parallel { .. } => {
                let depth = (p - self.origin).dot(self.look);
                (p - self.look * depth, self.look * depth)
            }
        };
        let dist = to.length();
        dist == 0.0 || cast(o, to / dist, solids, self.time).is_none_or(|(s, _)| s > dist)
    }

    /// The field of view as its driver would state it in the cloud: the
    /// cone or frustum from the origin, cut at the range, shrunk to the hull
    /// of the rays it casts (no space between the outermost rays and the
    /// nominal edge, which no ray crossed). On the image plane a frustum's
    /// outermost rays are the last grid lines inside it; a cone's grid holds
    /// every disc `diagonal` smaller than the cone's (a grid cell with a point
    /// in that disc has all four corners in the cone's). `None` for parallel
    /// rays, whose view is a prism, not a region from a point. Rays that span
    /// no area state a sliver (1e-9 rad).
    pub fn stated_field_of_view(&self) -> Option<message::FieldOfView> {
        if self.projection != Projection::Perspective {
            return None;
        }
        let angle = |tangent: f64| tangent.atan().max(1e-9);
        let aperture = match self.hull_tangents() {
            FieldOfView::Cone { half_angle: t } => message::Aperture::Cone {
                half_angle: angle(t),
            },
            FieldOfView::Frustum { half_x, half_y } => message::Aperture::Rectangle {
                right: self.right.to_array(),
                half_angles: [angle(half_x), angle(half_y)],
            },
        };
        Some(message::FieldOfView {
            apex: self.origin.to_array(),
            axis: self.look.to_array(),
            aperture,
            max_range: self.max_range,
        })
    }

    /// The tangents of the half angles of the rays' hull on the image plane
    /// (see [`Self::stated_field_of_view`]): a cone's radius, or a frustum's
    /// two half widths.
    fn hull_tangents(&self) -> FieldOfView {
        let last_line = |half: f64| Self::half_count(half.tan(), self.step) as f64 * self.step;
        match self.fov {
            FieldOfView::Cone { half_angle } => FieldOfView::Cone {
                half_angle: (half_angle.tan() - self.step * std::f64::consts::SQRT_2).max(0.0),
            },
            FieldOfView::Frustum { half_x, half_y } => FieldOfView::Frustum {
                half_x: last_line(half_x),
                half_y: last_line(half_y),
            },
        }
    }

    /// How deep `p` lies inside the hull of the rays and the range, by the
    /// harness's own geometry (0 or less outside): the distance to the
    /// nearest bounding surface, exact for these convex regions. Perspective
    /// rays: the cone `angle <= atan(t)` is `d sin(alpha - theta)` away, a
    /// frustum's face (through the origin, at `atan(t)` from the look) is
    /// `depth sin(beta) - |side| cos(beta)` away, the range ball `max_range -
    /// |p - origin|`. Parallel rays: a prism along the look from the aperture
    /// plane to `max_range`, its section the image region scaled by
    /// `reference`.
    pub fn depth_in_view(&self, p: DVec3) -> f64 {
        let to = p - self.origin;
        let depth = to.dot(self.look);
        let (x, y) = (to.dot(self.right), to.dot(self.up));
        let hull = self.hull_tangents();
        match self.projection {
            Projection::Perspective => {
                let lateral = match hull {
                    FieldOfView::Cone { half_angle: t } => {
                        let a = t.atan();
                        a.sin() * depth - a.cos() * x.hypot(y)
                    }
                    FieldOfView::Frustum { half_x, half_y } => {
                        let face = |side: f64, t: f64| {
                            let b = t.atan();
                            b.sin() * depth - b.cos() * side.abs()
                        };
                        face(x, half_x).min(face(y, half_y))
                    }
                };
                lateral.min(self.max_range - to.length())
            }
            Projection::Parallel { reference } => {
                let lateral = match hull {
                    FieldOfView::Cone { half_angle: t } => t * reference - x.hypot(y),
                    FieldOfView::Frustum { half_x, half_y } => {
                        (half_x * reference - x.abs()).min(half_y * reference - y.abs())
                    }
                };
                lateral.min(depth).min(self.max_range - depth)
            }
        }
    }

    /// Whether `p` is inside the field of view and within range (whatever
    /// stands in the way).
    pub fn covers(&self, p: DVec3) -> bool {
        let to = p - self.origin;
        let depth = to.dot(self.look);
        match self.projection {
            Projection::Perspective => {
                depth > 0.0
                    && to.length() <= self.max_range
                    && self
                        .fov
                        .contains(to.dot(self.right) / depth, to.dot(self.up) / depth)
            }
            Projection::Parallel { reference } => {
                depth > 0.0
                    && depth <= self.max_range
                    && self
                        .fov
                        .contains(to.dot(self.right) / reference, to.dot(self.up) / reference)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::soundness::solids::Body;

    /// The depth in the rays' hull is inside the nominal view, exact where
    /// it is positive (a ball of that radius stays covered, probed densely),
    /// and the stated field of view agrees with it.
    #[test]
    fn the_depth_in_view_is_exact_and_inside_the_view() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_pcg::Pcg64::seed_from_u64(4);
        let views = [
            FieldOfView::Cone { half_angle: 0.6 },
            FieldOfView::Frustum {
                half_x: 0.4,
                half_y: 0.7,
            },
        ];
        for (k, fov) in views.into_iter().enumerate() {
            for parallel in [false, true] {
                let mut sensor = Sensor::new(
                    DVec3::new(0.2, -0.1, 2.0),
                    DVec3::new(0.3, 0.1, -1.0),
                    fov,
                    3.0,
                    0.02,
                    0.0,
                );
                if parallel {
                    sensor.projection = Projection::Parallel { reference: 2.0 };
                }
                let stated = sensor.stated_field_of_view();
                let mut inside = 0;
                for _ in 0..3000 {
                    let p = DVec3::new(
                        rng.random_range(-2.0..2.0),
                        rng.random_range(-2.0..2.0),
                        rng.random_range(-1.0..2.5),
                    );
                    let depth = sensor.depth_in_view(p);
                    if let Some(f) = &stated {
                        let guard = shroud_guard::depth_inside(f, p);
                        assert!((guard - depth).abs() < 1e-9, "{k}: {guard} vs {depth}");
                    }
                    if depth <= 0.0 {
                        continue;
                    }
                    inside += 1;
                    for _ in 0..200 {
                        let d = DVec3::new(
                            rng.random_range(-1.0..1.0),
                            rng.random_range(-1.0..1.0),
                            rng.random_range(-1.0..1.0),
                        )
                        .normalize_or(DVec3::X);
                        assert!(sensor.covers(p + d * depth * 0.999), "{k} {parallel}");
                    }
                }
                assert!(inside > 50, "{k} {parallel}: {inside}");
            }
        }
    }

    #[test]
    fn a_downward_cone_scans_the_floor_within_range() {
        let sensor = Sensor::new(
            DVec3::new(0.0, 0.0, 2.0),
            -DVec3::Z,
            FieldOfView::Cone { half_angle: 0.5 },
            2.1,
            0.01,
            0.0,
        );
        let points = sensor.scan(&[]).points;
        assert!(points.len() > 1000);
        assert!(points.len() <= sensor.ray_count());
        // Within range only: the rim of the cone is at 2 / cos(0.5) > 2.1.
        assert!(points.len() < sensor.ray_count());
        for p in &points {
            assert!(p[2].abs() < 1e-6, "{p:?} is not on the floor");
            let r = (p[0] * p[0] + p[1] * p[1]).sqrt() as f64;
            assert!(r <= 2.0 * 0.5f64.tan() + 1e-6);
        }
        assert!(sensor.sees(DVec3::new(0.1, 0.0, 1.0), &[]));
        assert!(
            !sensor.sees(DVec3::new(1.5, 0.0, 1.0), &[]),
            "outside the cone"
        );
        assert!(
            !sensor.sees(DVec3::new(0.0, 0.0, 3.0), &[]),
            "behind the sensor"
        );
    }

    #[test]
    fn parallel_rays_keep_their_spacing() {
        let mut sensor = Sensor::new(
            DVec3::new(0.0, 0.0, 2.0),
            -DVec3::Z,
            FieldOfView::Frustum {
                half_x: 0.3,
                half_y: 0.3,
            },
            3.0,
            0.01,
            0.0,
        );
        sensor.projection = Projection::Parallel { reference: 2.0 };
        let points = sensor.scan(&[]).points;
        assert_eq!(points.len(), sensor.ray_count());
        let half = 2.0 * 0.3f64.tan() + 1e-6;
        assert!(points
            .iter()
            .all(|p| (p[0] as f64).abs() <= half && (p[1] as f64).abs() <= half));
        assert!((sensor.sampling_margin() - 0.02 * std::f64::consts::SQRT_2).abs() < 1e-12);
        // A column over the footprint is seen at every height below the sensor.
        assert!(sensor.sees(DVec3::new(0.6, 0.0, 1.9), &[]));
        assert!(!sensor.sees(DVec3::new(0.7, 0.0, 1.9), &[]));
    }

    /// The clearance from empty rays is the brute-force minimum over every
    /// empty ray of the scan (exact point-to-ray distances; point-to-line
    /// for parallel rays) less the gap, for both projections.
    #[test]
    fn clearance_from_empty_rays_matches_brute_force() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_pcg::Pcg64::seed_from_u64(9);
        let black = Solid {
            body: Body::Sphere { radius: 0.3 },
            centre: DVec3::new(0.2, 0.1, 0.8),
            velocity: DVec3::ZERO,
            black: true,
        };
        for parallel in [false, true] {
            let mut sensor = Sensor::new(
                DVec3::new(0.0, 0.0, 2.0),
                -DVec3::Z,
                FieldOfView::Frustum {
                    half_x: 0.5,
                    half_y: 0.4,
                },
                2.5,
                0.02,
                0.0,
            );
            if parallel {
                sensor.projection = Projection::Parallel { reference: 2.0 };
            }
            let scan = sensor.scan(&[black]);
            let index = sensor.empty_rays(&scan);
            let (n, m) = (
                (scan.columns / 2) as f64,
                (scan.empty.len() / scan.columns / 2) as f64,
            );
            let rays: Vec<(DVec3, DVec3)> = (0..scan.empty.len())
                .filter(|&k| scan.empty[k])
                .map(|k| {
                    let (i, j) = ((k % scan.columns) as f64 - n, (k / scan.columns) as f64 - m);
                    sensor.ray(i * sensor.step, j * sensor.step)
                })
                .collect();
            assert!(rays.len() > 100, "{parallel}: {}", rays.len());
            let diagonal = sensor.step * std::f64::consts::SQRT_2;
            for _ in 0..300 {
                let p = DVec3::new(
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                    rng.random_range(0.0..1.9),
                );
                let off = |(o, d): &(DVec3, DVec3)| {
                    let v = p - *o;
                    let along = v.dot(*d);
                    if along > 0.0 || parallel {
                        (v - *d * along).length()
                    } else {
                        v.length()
                    }
                };
                let nearest = rays.iter().map(off).fold(f64::INFINITY, f64::min);
                let gap = match sensor.projection {
                    Projection::Perspective => (p - sensor.origin).length() * diagonal,
                    Projection::Parallel { reference } => reference * diagonal,
                };
                let got = sensor.clearance_from_empty_rays(p, &index);
                assert!(
                    (got - (nearest - gap)).abs() < 1e-9,
                    "{parallel}: {got} vs {nearest}"
                );
            }
        }
    }

    #[test]
    fn black_solids_block_without_points_and_occlude() {
        let black = Solid {
            body: Body::Sphere { radius: 0.3 },
            centre: DVec3::new(0.0, 0.0, 1.0),
            velocity: DVec3::ZERO,
            black: true,
        };
        let sensor = Sensor::new(
            DVec3::new(0.0, 0.0, 2.0),
            -DVec3::Z,
            FieldOfView::Frustum {
                half_x: 0.1,
                half_y: 0.1,
            },
            5.0,
            0.01,
            0.0,
        );
        let scan = sensor.scan(&[black]);
        assert!(scan.points.is_empty());
        assert!(scan.empty.iter().all(|&e| e));
        let stated = sensor
            .stated_no_return(&scan)
            .expect("a black disc fills the view");
        assert_eq!(stated.apex, sensor.origin.to_array());
        // Every ray's direction lies in some cone.
        let directions = (0..scan.empty.len()).map(|k| {
            let n = (scan.columns / 2) as f64;
            let (i, j) = ((k % scan.columns) as f64 - n, (k / scan.columns) as f64 - n);
            sensor.ray(i * sensor.step, j * sensor.step).1
        });
        for d in directions {
            assert!(stated.cones.iter().any(|c| {
                let axis = DVec3::from_array(c.axis);
                axis.cross(d).length().atan2(axis.dot(d)) <= c.half_angle
            }));
        }
        assert_eq!(sensor.stated_no_return(&sensor.scan(&[])), None);
        assert!(!sensor.sees(DVec3::new(0.0, 0.0, 0.2), &[black]));
        assert!(sensor.sees(DVec3::new(0.0, 0.0, 1.5), &[black]));
        assert!(sensor.sampling_margin() > 0.0);
    }
}
