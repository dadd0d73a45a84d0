//! Height of a surface above the parameter plane. `None` marks where the
//! surrogate says nothing: outside the domain, or in a trimmed-out triangle.
//! Evaluation is `UniformCubicSurface::eval`, bit for bit what certification used.

use super::kept::kept_closed;
use super::view::SideView;
use glam::DVec3;

/// Surface height (frame `w`) at a place of the domain.
pub trait HeightQuery {
    /// At spline parameters `(s, t)`.
    fn height_at_param(&self, s: f64, t: f64) -> Option<f64>;

    /// At frame coordinates `(u, v)`.
    fn height_at_uv(&self, u: f64, v: f64) -> Option<f64>;

    /// Under (or over) a world point: at its projection along the frame's `w`.
    fn height_at_point(&self, p: DVec3) -> Option<f64>;
}

impl HeightQuery for SideView<'_> {
    #[inline]
    fn height_at_param(&self, s: f64, t: f64) -> Option<f64> {
        let inside = self.domain().contains_param(s, t) && kept_closed(self.trim(), s, t);
        inside.then(|| self.surface().eval(s, t))
    }

    fn height_at_uv(&self, u: f64, v: f64) -> Option<f64> {
        let (s, t) = self.params_of_uv(u, v);
        self.height_at_param(s, t)
    }

    fn height_at_point(&self, p: DVec3) -> Option<f64> {
        let (s, t, _) = self.locate(p);
        self.height_at_param(s, t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::query::tests::fixtures::{random_surrogate, trimmed_surrogate};
    use crate::Side;

    #[test]
    fn height_is_the_spline_value_inside_and_none_outside() {
        let sur = random_surrogate(6, 5, [1.0, 2.0, -3.0], 3);
        let view = SideView::new(&sur, Side::Upper).unwrap();
        for (s, t) in [(0.0, 0.0), (2.3, 1.7), (5.0, 4.0), (4.999, 0.001)] {
            assert_eq!(view.height_at_param(s, t), Some(view.surface().eval(s, t)));
        }
        for (s, t) in [(-0.01, 1.0), (5.01, 1.0), (1.0, 4.2), (f64::NAN, 1.0)] {
            assert_eq!(view.height_at_param(s, t), None, "({s}, {t})");
        }
    }

    #[test]
    fn uv_and_world_forms_agree_with_parameters() {
        let sur = random_surrogate(6, 5, [1.0, 2.0, -3.0], 4);
        let view = SideView::new(&sur, Side::Upper).unwrap();
        for (s, t) in [(0.5, 0.5), (3.25, 2.75), (4.0, 1.0)] {
            let (u, v) = sur.domain.frame_uv(s, t);
            let p = sur.frame.to_world(DVec3::new(u, v, 17.0));
            let (ps, pt, _) = view.locate(p);
            assert_eq!(view.height_at_point(p), view.height_at_param(ps, pt));
            // The frame coordinates of p give its parameters to the bit.
            assert_eq!(
                view.height_at_uv(p.dot(sur.frame.u), p.dot(sur.frame.v)),
                view.height_at_point(p)
            );
            let h = view.height_at_param(s, t).unwrap();
            assert!((view.height_at_point(p).unwrap() - h).abs() < 1e-9);
        }
    }

    #[test]
    fn trimmed_triangles_have_no_height() {
        // Cell (0, 0) keeps only its bottom triangle.
        let sur = trimmed_surrogate();
        let view = SideView::new(&sur, Side::Upper).unwrap();
        assert!(view.height_at_param(0.5, 0.1).is_some());
        assert!(view.height_at_param(0.5, 0.9).is_none());
        assert!(
            view.height_at_param(0.5, 0.5).is_some(),
            "the closed triangle includes its apex"
        );
    }
}
