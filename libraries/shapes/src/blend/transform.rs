//! Placing the child (Zou et al., Section 3): the rigid transform that takes the
//! initial position-normal pair (P_I, V_I) to the target (P_T, V_T), and the
//! 4-DOF local adjustment (Section 3.3, Fig. 7).

use glam::{DQuat, DVec3};
use shroud_msg::LocalAdjust;

/// `x -> rotation * x + translation`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidTransform {
    pub rotation: DQuat,
    pub translation: DVec3,
}

impl Default for RigidTransform {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl RigidTransform {
    pub const IDENTITY: Self = Self {
        rotation: DQuat::IDENTITY,
        translation: DVec3::ZERO,
    };

    /// Rotation by `rotation` about the point `pivot`.
    pub fn rotation_about(pivot: DVec3, rotation: DQuat) -> Self {
        Self {
            rotation,
            translation: pivot - rotation * pivot,
        }
    }

    pub fn translation(by: DVec3) -> Self {
        Self {
            rotation: DQuat::IDENTITY,
            translation: by,
        }
    }

    pub fn apply(&self, p: DVec3) -> DVec3 {
        self.rotation * p + self.translation
    }

    /// Directions rotate only.
    pub fn apply_vector(&self, v: DVec3) -> DVec3 {
        self.rotation * v
    }

    /// `self` after `first`: `x -> self(first(x))`.
    pub fn after(&self, first: &Self) -> Self {
        Self {
            rotation: (self.rotation * first.rotation).normalize(),
            translation: self.rotation * first.translation + self.translation,
        }
    }
}

/// The drop of Section 3.2 (Fig. 6): rotate about P_I so that V_I turns onto V_T
/// (the shortest arc, axis V_I x V_T), then translate by P_T - P_I. Normals need not
/// be unit; zero normals leave the rotation out.
pub fn drop_transform(p_i: DVec3, v_i: DVec3, p_t: DVec3, v_t: DVec3) -> RigidTransform {
    let (from, to) = (v_i.normalize_or_zero(), v_t.normalize_or_zero());
    let rotation = if from == DVec3::ZERO || to == DVec3::ZERO {
        DQuat::IDENTITY
    } else {
        DQuat::from_rotation_arc(from, to)
    };
    RigidTransform::translation(p_t - p_i).after(&RigidTransform::rotation_about(p_i, rotation))
}

/// The transform a [`LocalAdjust`] (the joystick of Section 3.3, Fig. 7)
/// makes about a placed child. A trait because the adjustment is a wire type
/// (`shroud_msg`) that knows no transforms.
pub trait AdjustTransform {
    /// The transform about the placed centroid `p_t` with normal `v_t`: spin about
    /// the normal, then tilt about the centroid, then slide along the tilted normal.
    fn transform(&self, p_t: DVec3, v_t: DVec3) -> RigidTransform;

    /// The normal at the centroid after this adjustment.
    fn normal(&self, v_t: DVec3) -> DVec3 {
        self.transform(DVec3::ZERO, v_t)
            .apply_vector(v_t.normalize_or(DVec3::Z))
    }
}

impl AdjustTransform for LocalAdjust {
    fn transform(&self, p_t: DVec3, v_t: DVec3) -> RigidTransform {
        let n = v_t.normalize_or(DVec3::Z);
        let (u, v) = n.any_orthonormal_pair();
        let spin = DQuat::from_axis_angle(n, self.spin);
        let tilt =
            DQuat::from_axis_angle(v, self.tilt[1]) * DQuat::from_axis_angle(u, self.tilt[0]);
        let rotate = RigidTransform::rotation_about(p_t, tilt * spin);
        RigidTransform::translation(tilt * n * self.lift).after(&rotate)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn composition_order() {
        let a = RigidTransform::translation(DVec3::X);
        let b = RigidTransform::rotation_about(DVec3::ZERO, DQuat::from_rotation_z(1.0));
        let p = DVec3::new(0.3, -0.2, 0.5);
        assert!((b.after(&a).apply(p) - b.apply(a.apply(p))).length() < 1e-12);
    }

    #[test]
    fn adjust_moves_along_and_spins_about_the_normal() {
        let p_t = DVec3::new(1.0, 2.0, 3.0);
        let n = DVec3::new(0.0, 1.0, 1.0).normalize();
        let lift = LocalAdjust {
            lift: 0.5,
            ..Default::default()
        }
        .transform(p_t, n);
        assert!((lift.apply(p_t) - (p_t + 0.5 * n)).length() < 1e-12);
        let spin = LocalAdjust {
            spin: 1.2,
            ..Default::default()
        }
        .transform(p_t, n);
        assert!((spin.apply(p_t + n) - (p_t + n)).length() < 1e-12);
        let tilt = LocalAdjust {
            tilt: [0.3, -0.2],
            ..Default::default()
        };
        assert!((tilt.transform(p_t, n).apply(p_t) - p_t).length() < 1e-12);
        assert!((tilt.normal(n).dot(n) - (0.3f64.cos() * 0.2f64.cos())).abs() < 1e-12);
    }
}
