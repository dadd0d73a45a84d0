//! The world an emulated device measures: a triangle mesh (a sim scene's or a
//! user's) seen from a mount that may tilt or turn on the wall clock.

use super::ray::{RayReturn, RaySource};
use crate::scanner::Bvh;
use glam::DVec3;
use shroud_drivers::assembly::{MountMotion, MovingMount};
use std::sync::Arc;

/// Rays from a (moving) mount into a mesh. The mount's sweep profile is read
/// at `start_unix_ns + time`, so a node configured with the same profile
/// places the rays where they were cast.
pub struct MeshRays {
    bvh: Arc<Bvh>,
    mount: MovingMount,
    start_unix_ns: u64,
}

impl MeshRays {
    /// `mount.motion` must be fixed or a profile: an emulated unit has no
    /// joint to read.
    pub fn new(bvh: Arc<Bvh>, mount: MovingMount, start_unix_ns: u64) -> Result<Self, String> {
        if matches!(mount.motion, MountMotion::Joint { .. }) {
            return Err("an emulated mount moves by a sweep profile, not a joint".into());
        }
        Ok(Self {
            bvh,
            mount,
            start_unix_ns,
        })
    }
}

impl RaySource for MeshRays {
    fn cast(&self, angle: f64, time: f64, max_range: f64) -> Option<RayReturn> {
        if !(time.is_finite() && time >= 0.0 && max_range > 0.0) {
            return None;
        }
        let unix_ns = self.start_unix_ns.saturating_add((time * 1e9) as u64);
        let (tilt, _) = match &self.mount.motion {
            MountMotion::Profile(p) => (p.angle_at(unix_ns), 0),
            _ => (0.0, 0),
        };
        let pose = self.mount.pose_at_angle(tilt);
        let direction = pose.rotation * DVec3::new(angle.cos(), angle.sin(), 0.0);
        let hit = self.bvh.intersect(
            pose.translation.as_vec3().to_array(),
            direction.as_vec3().to_array(),
            max_range as f32,
        )?;
        let normal = DVec3::from_array(hit.normal.map(f64::from));
        // Lambertian-ish: a surface facing the ray returns more light.
        let facing = normal.dot(direction).abs().clamp(0.0, 1.0);
        Some(RayReturn {
            range: hit.distance as f64,
            reflectance: 0.2 + 0.8 * facing,
        })
    }
}
