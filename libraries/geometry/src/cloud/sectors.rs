//! Overlapping sectors of a sensor's field of view, each a cone that a
//! surface fitted along its own axis can answer for more tightly than one
//! surface for the whole view.
//!
//! An upper surface fitted along a direction counts everything beyond it *in
//! that direction* as occupied. Along the axis of a wide perspective view the
//! columns stray from the sensor's rays by up to the view's half angle, so a
//! solid's top shades a column the sensor saw past its edge, and the space
//! there counts as occupied though a ray crossed it. Along a sector's own
//! axis the columns stray from the rays by at most the sector's half angle.
//!
//! A sector is cell `(column, row)` of an `n x n` grid on the view's image
//! plane (the plane at unit distance along its axis: tangents of the angles,
//! over the rectangle's half angles or the square around a cone). Its cone is
//! centred on the ray through the cell's centre and reaches `reach` times the
//! cell's angular half-diagonal, but never past the view's boundary: a
//! sector states only space the sensor looked at. Sectors with `reach > 1`
//! overlap, so that a shape near the edge of one lies deep inside another.
//!
//! A sector's cloud holds every point of the view's cloud whose ray lies in
//! the sector's cone ([`points_in_sector`]): the surface fitted from it then
//! bounds everything the sensor saw in the sector.

use glam::DVec3;
use shroud_msg::{Aperture, DarkCone, FieldOfView, NoReturn};

/// Largest grid side: 64 sectors, each fitted on every cloud.
pub const MAX_SECTOR_GRID: usize = 8;

/// A sector narrower than this (radians, about 0.6 degrees) has no room for
/// anything a guard could clear.
const MIN_HALF_ANGLE: f64 = 0.01;

/// Kept between a sector's cone and the view's boundary, and added when
/// points are sorted into it (directions computed in f64 from f32 points).
const ROUNDING: f64 = 1e-9;

/// Why a sector cannot be formed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SectorError {
    #[error("sector grid {0} is not 1 to {MAX_SECTOR_GRID}")]
    Grid(usize),
    #[error("sector {index} is not in a {grid} x {grid} grid")]
    Index { index: usize, grid: usize },
    #[error("sector reach {0} is not a number >= 1")]
    Reach(f64),
    #[error("the field of view is invalid: {0}")]
    FieldOfView(String),
    #[error("sector {index} of the {grid} x {grid} grid has no room inside the field of view")]
    NoRoom { index: usize, grid: usize },
}

/// The field of view's axis and image-plane basis, renormalised (the wire
/// allows directions within 1e-6 of unit), with the tangents of its half
/// angles along `right` and `up`.
struct ImagePlane {
    axis: DVec3,
    right: DVec3,
    up: DVec3,
    tangents: [f64; 2],
}

impl ImagePlane {
    fn of(fov: &FieldOfView) -> Self {
        let axis = DVec3::from_array(fov.axis).normalize();
        let (right, tangents) = match fov.aperture {
            Aperture::Cone { half_angle } => (axis.any_orthonormal_vector(), [half_angle.tan(); 2]),
            Aperture::Rectangle { right, half_angles } => {
                let right = DVec3::from_array(right);
                let right = (right - right.dot(axis) * axis).normalize();
                (right, [half_angles[0].tan(), half_angles[1].tan()])
            }
        };
        Self {
            axis,
            right,
            up: axis.cross(right),
            tangents,
        }
    }

    /// The unit direction through image-plane point (u, v).
    fn ray(&self, u: f64, v: f64) -> DVec3 {
        (self.axis + u * self.right + v * self.up).normalize()
    }
}

/// The angle from unit direction `c` to the boundary of `fov`'s aperture (0
/// or less when `c` is outside it). Each boundary is a plane through the
/// apex, or for a cone the cone itself.
fn angle_to_boundary(fov: &FieldOfView, plane: &ImagePlane, c: DVec3) -> f64 {
    match fov.aperture {
        Aperture::Cone { half_angle } => half_angle - c.dot(plane.axis).clamp(-1.0, 1.0).acos(),
        Aperture::Rectangle { half_angles, .. } => {
            // A face's inward unit normal is axis sin(h) - side cos(h).
            let face = |side: DVec3, h: f64| {
                let inward = plane.axis * h.sin() - side * h.cos();
                c.dot(inward).clamp(-1.0, 1.0).asin()
            };
            [
                face(plane.right, half_angles[0]),
                face(-plane.right, half_angles[0]),
                face(plane.up, half_angles[1]),
                face(-plane.up, half_angles[1]),
            ]
            .into_iter()
            .fold(f64::INFINITY, f64::min)
        }
    }
}

/// Refuses a grid side outside `1..=MAX_SECTOR_GRID` and a reach below 1.
pub fn check_sectors(grid: usize, reach: f64) -> Result<(), SectorError> {
    if !(1..=MAX_SECTOR_GRID).contains(&grid) {
        return Err(SectorError::Grid(grid));
    }
    if !(reach >= 1.0) {
        return Err(SectorError::Reach(reach));
    }
    Ok(())
}

/// Sector `index` (row-major: `row * grid + column`) of `fov`'s `grid x grid`
/// sectors, as the cone field of view it states: apex and range of `fov`,
/// axis through the cell's centre, half angle `reach` times the cell's
/// angular half-diagonal, at most the angle to `fov`'s boundary.
pub fn sector(
    fov: &FieldOfView,
    grid: usize,
    index: usize,
    reach: f64,
) -> Result<FieldOfView, SectorError> {
    check_sectors(grid, reach)?;
    if index >= grid * grid {
        return Err(SectorError::Index { index, grid });
    }
    fov.validate()
        .map_err(|e| SectorError::FieldOfView(e.to_string()))?;
    let plane = ImagePlane::of(fov);
    let (column, row) = ((index % grid) as f64, (index / grid) as f64);
    let n = grid as f64;
    // The cell's centre and half sizes on the image plane.
    let [tu, tv] = plane.tangents;
    let (u, v) = (
        tu * ((2.0 * column + 1.0) / n - 1.0),
        tv * ((2.0 * row + 1.0) / n - 1.0),
    );
    let (du, dv) = (tu / n, tv / n);
    let centre = plane.ray(u, v);
    let half_diagonal = [(-1.0, -1.0), (-1.0, 1.0), (1.0, -1.0), (1.0, 1.0)]
        .into_iter()
        .map(|(su, sv)| {
            let corner = plane.ray(u + su * du, v + sv * dv);
            centre.dot(corner).clamp(-1.0, 1.0).acos()
        })
        .fold(0.0, f64::max);
    let half_angle = (reach * half_diagonal).min(angle_to_boundary(fov, &plane, centre) - ROUNDING);
    if !(half_angle >= MIN_HALF_ANGLE) {
        return Err(SectorError::NoRoom { index, grid });
    }
    Ok(FieldOfView {
        apex: fov.apex,
        axis: centre.to_array(),
        aperture: Aperture::Cone { half_angle },
        max_range: fov.max_range,
    })
}

/// Appends to `out` every point of `points` whose ray from the sector's apex
/// lies within its cone (grown by a rounding margin, so no point of the
/// sector is left out; a point at the apex counts). Range is not checked: a
/// sensor returns nothing beyond it.
pub fn points_in_sector(sector: &FieldOfView, points: &[[f32; 3]], out: &mut Vec<[f32; 3]>) {
    let Aperture::Cone { half_angle } = sector.aperture else {
        out.extend_from_slice(points);
        return;
    };
    let apex = DVec3::from_array(sector.apex);
    let axis = DVec3::from_array(sector.axis).normalize();
    let cos = (half_angle + ROUNDING).min(std::f64::consts::PI).cos();
    out.extend(points.iter().filter(|p| {
        let d = DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64) - apex;
        // Within the cone when cos(angle) >= cos(half angle), without a
        // division: a point at the apex has d = 0 and passes.
        d.dot(axis) >= cos * d.length()
    }));
}

/// The cones of `no_return` that reach into `sector`. A cone from the same
/// apex that does not is outside the sector, where everything counts as
/// unseen already, so dropping it changes no distance to unseen space; with
/// another apex every cone is kept.
pub fn no_return_in_sector(sector: &FieldOfView, no_return: &NoReturn) -> NoReturn {
    let Aperture::Cone { half_angle } = sector.aperture else {
        return no_return.clone();
    };
    if no_return.apex != sector.apex {
        return no_return.clone();
    }
    let axis = DVec3::from_array(sector.axis).normalize();
    let reaches = |c: &&DarkCone| {
        let cone_axis = DVec3::from_array(c.axis).normalize();
        let between = axis.dot(cone_axis).clamp(-1.0, 1.0).acos();
        between <= half_angle + c.half_angle + ROUNDING
    };
    NoReturn {
        apex: no_return.apex,
        cones: no_return.cones.iter().filter(reaches).copied().collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use shroud_msg::sample_field_of_view;

    fn cone(half_angle: f64) -> FieldOfView {
        FieldOfView {
            apex: [0.5, -0.2, 2.0],
            axis: [0.0, 0.0, -1.0],
            aperture: Aperture::Cone { half_angle },
            max_range: 4.0,
        }
    }

    /// A tilted image rectangle whose `right` is as far from perpendicular
    /// to its axis as the wire allows.
    fn tilted_rectangle() -> FieldOfView {
        let axis = DVec3::new(0.3, -0.2, -1.0).normalize();
        let right = (axis.any_orthonormal_vector() + axis * 9e-7).normalize();
        let fov = FieldOfView {
            apex: [0.2, 0.1, 1.8],
            axis: axis.to_array(),
            aperture: Aperture::Rectangle {
                right: right.to_array(),
                half_angles: [0.8, 0.3],
            },
            max_range: 3.0,
        };
        fov.validate().unwrap();
        fov
    }

    /// Whether unit direction `d` lies inside `fov`'s aperture, by its
    /// definition (tangents along the axis, or the angle to it).
    fn inside(fov: &FieldOfView, d: DVec3) -> bool {
        let axis = DVec3::from_array(fov.axis).normalize();
        let along = d.dot(axis);
        match fov.aperture {
            Aperture::Cone { half_angle } => along > 0.0 && d.angle_between(axis) <= half_angle,
            Aperture::Rectangle { right, half_angles } => {
                let right = DVec3::from_array(right);
                let right = (right - right.dot(axis) * axis).normalize();
                let up = axis.cross(right);
                along > 0.0
                    && (d.dot(right) / along).abs() <= half_angles[0].tan()
                    && (d.dot(up) / along).abs() <= half_angles[1].tan()
            }
        }
    }

    /// Directions on the sector cone's boundary, all of which must lie in the
    /// parent field of view.
    fn boundary_rays(s: &FieldOfView) -> Vec<DVec3> {
        let axis = DVec3::from_array(s.axis);
        let Aperture::Cone { half_angle } = s.aperture else {
            panic!("a sector is a cone")
        };
        let (a, b) = axis.any_orthonormal_pair();
        (0..360)
            .map(|k| {
                let phi = (k as f64).to_radians();
                (axis * half_angle.cos() + (a * phi.cos() + b * phi.sin()) * half_angle.sin())
                    .normalize()
            })
            .collect()
    }

    #[test]
    fn every_sector_lies_inside_its_field_of_view_by_brute_force() {
        for fov in [
            sample_field_of_view(),
            tilted_rectangle(),
            cone(0.7),
            cone(0.35),
        ] {
            for grid in 1..=4 {
                for index in 0..grid * grid {
                    for reach in [1.0, 1.5, f64::INFINITY] {
                        let s = match sector(&fov, grid, index, reach) {
                            Ok(s) => s,
                            // A cone's corner cells may lie outside it.
                            Err(SectorError::NoRoom { .. }) => {
                                assert!(matches!(fov.aperture, Aperture::Cone { .. }));
                                continue;
                            }
                            Err(e) => panic!("{e}"),
                        };
                        s.validate().unwrap();
                        assert_eq!(s.apex, fov.apex);
                        assert!(
                            boundary_rays(&s).iter().all(|d| inside(&fov, *d)),
                            "{fov:?} grid {grid} sector {index} reach {reach}: {s:?}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn sectors_cover_the_image_plane_cells_they_are_named_after() {
        // With reach 1 a sector is the cell's circumscribed cone, cut by the
        // boundary only: the cell's centre ray is its axis.
        let fov = sample_field_of_view();
        let plane = ImagePlane::of(&fov);
        let s = sector(&fov, 2, 3, 1.0).unwrap();
        let axis = DVec3::from_array(s.axis);
        let expected = plane.ray(plane.tangents[0] / 2.0, plane.tangents[1] / 2.0);
        assert!((axis - expected).length() < 1e-12);
        // The middle sector of an odd grid looks along the view's axis.
        let middle = sector(&fov, 3, 4, 1.0).unwrap();
        assert!((DVec3::from_array(middle.axis) - plane.axis).length() < 1e-12);
    }

    #[test]
    fn wider_reach_gives_wider_sectors_up_to_the_boundary() {
        let fov = cone(0.7);
        let half = |reach| match sector(&fov, 3, 4, reach).unwrap().aperture {
            Aperture::Cone { half_angle } => half_angle,
            Aperture::Rectangle { .. } => unreachable!(),
        };
        assert!(half(1.0) < half(1.5));
        assert!((half(f64::INFINITY) - 0.7).abs() < 1e-6);
    }

    #[test]
    fn bad_grids_indices_and_reaches_are_named() {
        let fov = cone(0.5);
        assert_eq!(sector(&fov, 0, 0, 1.0), Err(SectorError::Grid(0)));
        assert_eq!(sector(&fov, 9, 0, 1.0), Err(SectorError::Grid(9)));
        assert_eq!(
            sector(&fov, 2, 4, 1.0),
            Err(SectorError::Index { index: 4, grid: 2 })
        );
        assert!(matches!(
            sector(&fov, 2, 0, f64::NAN),
            Err(SectorError::Reach(_))
        ));
        assert!(matches!(
            sector(&fov, 2, 0, 0.5),
            Err(SectorError::Reach(_))
        ));
        let mut bad = fov;
        bad.max_range = -1.0;
        assert!(matches!(
            sector(&bad, 2, 0, 1.0),
            Err(SectorError::FieldOfView(_))
        ));
        // A cone's corner cells of a fine grid lie outside it.
        assert_eq!(
            sector(&cone(0.5), 8, 0, 1.0),
            Err(SectorError::NoRoom { index: 0, grid: 8 })
        );
    }

    #[test]
    fn a_sector_keeps_exactly_the_points_whose_rays_it_holds() {
        let fov = sample_field_of_view();
        let s = sector(&fov, 2, 1, 1.5).unwrap();
        let apex = DVec3::from_array(fov.apex);
        let axis = DVec3::from_array(s.axis);
        let Aperture::Cone { half_angle } = s.aperture else {
            unreachable!()
        };
        let mut points = vec![];
        for i in -20..=20 {
            for j in -20..=20 {
                let p = apex + DVec3::new(i as f64 * 0.1, j as f64 * 0.1, -2.0);
                points.push(p.as_vec3().to_array());
            }
        }
        points.push(fov.apex.map(|v| v as f32));
        let mut kept = vec![];
        points_in_sector(&s, &points, &mut kept);
        for p in &points {
            let d = DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64) - apex;
            let angle = if d.length() == 0.0 {
                0.0
            } else {
                d.angle_between(axis)
            };
            if angle < half_angle - 1e-6 {
                assert!(kept.contains(p), "{p:?} at {angle} rad is in the sector");
            } else if angle > half_angle + 1e-6 {
                assert!(!kept.contains(p), "{p:?} at {angle} rad is not");
            }
        }
        assert!(kept.len() > 10 && kept.len() < points.len());
    }

    #[test]
    fn a_sector_keeps_the_dark_cones_that_reach_into_it() {
        let fov = cone(0.6);
        let s = sector(&fov, 2, 0, 1.0).unwrap();
        let axis = DVec3::from_array(s.axis);
        let Aperture::Cone { half_angle } = s.aperture else {
            unreachable!()
        };
        let (e1, _) = axis.any_orthonormal_pair();
        // Cones at growing angles from the sector's axis, each 0.05 wide.
        let cones: Vec<DarkCone> = (0..40)
            .map(|k| {
                let angle = k as f64 * 0.025;
                let dir = axis * angle.cos() + e1 * angle.sin();
                DarkCone {
                    axis: dir.to_array(),
                    half_angle: 0.05,
                }
            })
            .collect();
        let all = NoReturn {
            apex: fov.apex,
            cones: cones.clone(),
        };
        let kept = no_return_in_sector(&s, &all);
        for (k, c) in cones.iter().enumerate() {
            let reaches = k as f64 * 0.025 <= half_angle + 0.05;
            assert_eq!(kept.cones.contains(c), reaches, "cone {k}");
        }
        let elsewhere = NoReturn {
            apex: [9.0, 9.0, 9.0],
            cones,
        };
        assert_eq!(no_return_in_sector(&s, &elsewhere), elsewhere);
    }
}
