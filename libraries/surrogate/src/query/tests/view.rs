//! Views refuse surrogates whose parts disagree, instead of panicking later.

use super::fixtures::{assemble, domain, random_surrogate};
use crate::query::{QueryError, SideView, SurrogateView};
use crate::{Side, TrimMask};

#[test]
fn a_consistent_surrogate_gives_views_of_its_sides() {
    let sur = random_surrogate(5, 4, [0.0, 0.0, -1.0], 1);
    let view = SurrogateView::new(&sur).unwrap();
    assert_eq!(view.sides().count(), 1);
    assert!(view.upper().is_some() && view.lower().is_none());
    assert_eq!(
        SideView::new(&sur, Side::Lower).unwrap_err(),
        QueryError::MissingSide(Side::Lower)
    );
}

#[test]
fn mismatched_parts_are_reported() {
    let mut sur = random_surrogate(5, 4, [0.0, 0.0, -1.0], 1);
    sur.trim = TrimMask::full(3, 3);
    assert!(matches!(
        SurrogateView::new(&sur),
        Err(QueryError::TrimMismatch { .. })
    ));

    let mut sur = random_surrogate(5, 4, [0.0, 0.0, -1.0], 1);
    sur.domain.cols = 6;
    sur.trim = TrimMask::full(5, 3);
    assert!(matches!(
        SurrogateView::new(&sur),
        Err(QueryError::GridMismatch { .. })
    ));

    let mut sur = random_surrogate(5, 4, [0.0, 0.0, -1.0], 1);
    if let Some(up) = sur.upper.as_mut() {
        up.surface.coefficients[7] = f64::NAN;
    }
    let err = SurrogateView::new(&sur).unwrap_err();
    assert_eq!(
        err,
        QueryError::NonFiniteCoefficient {
            side: Side::Upper,
            index: 7
        }
    );
    assert!(err.to_string().contains("coefficient 7"));

    let mut sur = random_surrogate(5, 4, [0.0, 0.0, -1.0], 1);
    sur.domain.u_step = 0.0;
    assert!(matches!(
        SurrogateView::new(&sur),
        Err(QueryError::BadDomain(_))
    ));

    let mut sur = random_surrogate(5, 4, [0.0, 0.0, -1.0], 1);
    sur.lower = sur.upper.clone();
    assert!(matches!(
        SurrogateView::new(&sur),
        Err(QueryError::SideMismatch {
            slot: Side::Lower,
            ..
        })
    ));
}

#[test]
fn a_surrogate_without_surfaces_is_refused() {
    let sur = assemble(
        [0.0, 0.0, -1.0],
        domain(3, 3),
        TrimMask::full(2, 2),
        [None, None],
    );
    assert_eq!(SurrogateView::new(&sur).unwrap_err(), QueryError::NoSurface);
}
