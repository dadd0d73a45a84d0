//! Drag-and-drop on the parent's surface (Zou et al., Section 3.2): the target point
//! P_T and normal V_T under the cursor from the discrete depth buffer, the
//! Bresenham correction when the cursor leaves the surface (Fig. 4), and a session
//! that turns a 2D cursor path into the child's rigid transform.

use super::camera::Camera;
use super::depth::{BlockDepth, DepthImage};
use super::error::BlendError;
use super::transform::{drop_transform, RigidTransform};
use glam::{DVec2, DVec3};
use shroud_geometry::cloud::fit_plane;

/// The pixels of the digital line from `a` to `b`, both included (Bresenham).
pub fn bresenham(a: (i64, i64), b: (i64, i64)) -> Vec<(i64, i64)> {
    let (dx, dy) = ((b.0 - a.0).abs(), -(b.1 - a.1).abs());
    let (sx, sy) = (
        if a.0 < b.0 { 1 } else { -1 },
        if a.1 < b.1 { 1 } else { -1 },
    );
    let mut err = dx + dy;
    let (mut x, mut y) = a;
    let mut line = Vec::with_capacity((dx - dy) as usize + 1);
    loop {
        line.push((x, y));
        if (x, y) == b {
            return line;
        }
        let e2 = 2 * err;
        if e2 >= dy {
            err += dy;
            x += sx;
        }
        if e2 <= dx {
            err += dx;
            y += sy;
        }
    }
}

/// C_n2d' of Fig. 4: walking the Bresenham line from `from` to `to`, the last pixel
/// on the surface (discrete depth below 1.0) before the walk first leaves it. If
/// `from` is off the surface the walk starts where the line first meets it. `None`
/// if the line never meets the surface.
pub fn last_on_surface(
    blocks: &BlockDepth,
    from: (i64, i64),
    to: (i64, i64),
) -> Option<(i64, i64)> {
    let mut last = None;
    for pixel in bresenham(from, to) {
        if blocks.on_surface(pixel.0, pixel.1) {
            last = Some(pixel);
        } else if last.is_some() {
            break;
        }
    }
    last
}

/// P_T and V_T at `pixel` (on the surface). The samples behind the block of
/// `pixel` and its 8-connected neighbours that show the surface (Fig. 5) are
/// unprojected and fitted with a least-squares plane; V_T is its normal, turned
/// toward the camera, and P_T is where the cursor's ray meets that plane. (The
/// paper unprojects the cursor with its block's minimum depth; on a slanted
/// surface that lifts P_T off the surface by up to a block's depth range, so the
/// plane is used instead, falling back to the block's own sample.)
pub fn surface_target(
    blocks: &BlockDepth,
    camera: &Camera,
    pixel: (i64, i64),
) -> Result<(DVec3, DVec3), BlendError> {
    let (c, r) = blocks
        .block_of(pixel.0, pixel.1)
        .ok_or(BlendError::NotOnSurface)?;
    let (c, r) = (c as i64, r as i64);
    let (at, depth) = blocks.sample(c, r).ok_or(BlendError::NotOnSurface)?;
    let own = camera.unproject(at, f64::from(depth));
    let mut samples = Vec::with_capacity(9);
    for dr in -1i64..=1 {
        for dc in -1i64..=1 {
            if let Some((q, d)) = blocks.sample(c + dc, r + dr) {
                samples.push(camera.unproject(q, f64::from(d)));
            }
        }
    }
    let fit = fit_plane(samples.iter().copied())
        .filter(|f| f.is_two_dimensional(1e-6))
        .ok_or(BlendError::NoTargetNormal)?;
    let normal = fit.plane.normal;
    let v_t = if normal.dot(camera.eye - own) < 0.0 {
        -normal
    } else {
        normal
    };
    let centre = DVec2::new(pixel.0 as f64 + 0.5, pixel.1 as f64 + 0.5);
    let near = camera.unproject(centre, 0.0);
    let ray = camera.unproject(centre, 1.0) - near;
    let along = ray.dot(v_t);
    let spread = samples.iter().map(|p| p.distance(own)).fold(0.0, f64::max);
    let p_t = if along.abs() > 1e-12 {
        let hit = near + ray * ((fit.plane.origin - near).dot(v_t) / along);
        if hit.distance(own) <= 2.0 * spread.max(f64::MIN_POSITIVE) {
            hit
        } else {
            own
        }
    } else {
        own
    };
    Ok((p_t, v_t))
}

/// An interactive drag: the parent's discrete depth buffer for one camera, the
/// child's current position-normal pair and its accumulated transform.
#[derive(Debug, Clone)]
pub struct DragSession {
    camera: Camera,
    blocks: BlockDepth,
    transform: RigidTransform,
    p_i: DVec3,
    v_i: DVec3,
    /// C_2d: where the child's centroid shows on screen.
    centroid_2d: DVec2,
    /// P_2d: the previous cursor position.
    cursor: DVec2,
}

impl DragSession {
    /// Renders the parent for `camera`, discretises with `block` pixels (Section 3.2)
    /// and "pastes" the child (pair `p_i`, `v_i` in its own coordinates) at the
    /// surface point under `cursor` (Fig. 1b).
    pub fn paste(
        parent: &[DVec3],
        camera: Camera,
        block: usize,
        p_i: DVec3,
        v_i: DVec3,
        cursor: DVec2,
    ) -> Result<Self, BlendError> {
        camera.validate()?;
        let image = DepthImage::render(parent, &camera);
        let blocks = BlockDepth::from_image(&image, block);
        let pixel = (cursor.x.floor() as i64, cursor.y.floor() as i64);
        if !blocks.on_surface(pixel.0, pixel.1) {
            return Err(BlendError::NotOnSurface);
        }
        let (p_t, v_t) = surface_target(&blocks, &camera, pixel)?;
        Ok(Self {
            camera,
            blocks,
            transform: drop_transform(p_i, v_i, p_t, v_t),
            p_i: p_t,
            v_i: v_t,
            centroid_2d: cursor,
            cursor,
        })
    }

    /// Moves the cursor to `cursor`: the centroid should follow to
    /// C_n2d = C_2d + (P_n2d - P_2d); if that leaves the surface it stops at the last
    /// surface pixel on the way (Fig. 4). The child turns and moves from (P_I, V_I)
    /// to the new (P_T, V_T), which becomes the next (P_I, V_I). Returns this step.
    pub fn drag_to(&mut self, cursor: DVec2) -> Result<RigidTransform, BlendError> {
        if !cursor.is_finite() {
            return Err(BlendError::NotOnSurface);
        }
        let wanted = self.centroid_2d + (cursor - self.cursor);
        let from = (
            self.centroid_2d.x.floor() as i64,
            self.centroid_2d.y.floor() as i64,
        );
        let to = (wanted.x.floor() as i64, wanted.y.floor() as i64);
        let pixel = last_on_surface(&self.blocks, from, to).ok_or(BlendError::NotOnSurface)?;
        let (p_t, v_t) = surface_target(&self.blocks, &self.camera, pixel)?;
        let step = drop_transform(self.p_i, self.v_i, p_t, v_t);
        self.transform = step.after(&self.transform);
        (self.p_i, self.v_i) = (p_t, v_t);
        self.centroid_2d = if pixel == to {
            wanted
        } else {
            DVec2::new(pixel.0 as f64 + 0.5, pixel.1 as f64 + 0.5)
        };
        self.cursor = cursor;
        Ok(step)
    }

    /// The child's transform from its own coordinates to where it is now.
    pub fn transform(&self) -> RigidTransform {
        self.transform
    }

    /// The current (P_T, V_T).
    pub fn placement(&self) -> (DVec3, DVec3) {
        (self.p_i, self.v_i)
    }

    pub fn blocks(&self) -> &BlockDepth {
        &self.blocks
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bresenham_endpoints_and_steps() {
        let line = bresenham((0, 0), (5, 2));
        assert_eq!(line.first(), Some(&(0, 0)));
        assert_eq!(line.last(), Some(&(5, 2)));
        assert_eq!(line.len(), 6);
        assert!(line
            .windows(2)
            .all(|w| (w[1].0 - w[0].0).abs() <= 1 && (w[1].1 - w[0].1).abs() <= 1));
        assert_eq!(bresenham((3, 3), (3, 3)), vec![(3, 3)]);
        assert_eq!(bresenham((0, 0), (-2, -4)).len(), 5);
    }
}
