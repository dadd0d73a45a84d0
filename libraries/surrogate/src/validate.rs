//! The invariants of a published surrogate, checked on everything read from a file
//! or the wire, so that evaluating a loaded surrogate can never index out of bounds
//! or silently use a surface that was not certified.

use super::error::SurrogateDefect;
use crate::trim::ALL;
use crate::{Domain, SafeSurface, Side, Surrogate, TrimMask, MAX_GRID};
use glam::DVec3;
use shroud_geometry::math::Frame;

/// Tolerance on unit length and orthogonality of the frame axes. Frames are built
/// in f64 by normalisation and cross products, so they are exact to a few ulps.
const AXIS_TOLERANCE: f64 = 1e-9;

/// Checks every invariant listed in `docs/formats.md` ("Validation").
pub fn validate_surrogate(surrogate: &Surrogate) -> Result<(), SurrogateDefect> {
    validate_frame(&surrogate.frame)?;
    validate_domain(&surrogate.domain)?;
    validate_trim(&surrogate.trim, &surrogate.domain)?;
    if surrogate.upper.is_none() && surrogate.lower.is_none() {
        return Err(SurrogateDefect::NoSurface);
    }
    for (slot, surface) in [
        (Side::Upper, &surrogate.upper),
        (Side::Lower, &surrogate.lower),
    ] {
        if let Some(surface) = surface {
            validate_surface(slot, surface, &surrogate.domain, &surrogate.frame)?;
        }
    }
    Ok(())
}

/// Lower-case name of a side, as used in messages and in the JSON format.
pub fn side_name(side: Side) -> &'static str {
    match side {
        Side::Upper => "upper",
        Side::Lower => "lower",
    }
}

fn validate_frame(frame: &Frame) -> Result<(), SurrogateDefect> {
    let axes = [
        ("direction", frame.direction),
        ("u", frame.u),
        ("v", frame.v),
        ("w", frame.w),
    ];
    for (axis, a) in axes {
        if !a.is_finite() {
            return Err(SurrogateDefect::Frame {
                axis,
                reason: "not finite",
            });
        }
        if (a.length() - 1.0).abs() > AXIS_TOLERANCE {
            return Err(SurrogateDefect::Frame {
                axis,
                reason: "not of unit length",
            });
        }
    }
    let close = |a: DVec3, b: DVec3| (a - b).length() <= AXIS_TOLERANCE;
    if !close(frame.w, -frame.direction) {
        return Err(SurrogateDefect::Frame {
            axis: "w",
            reason: "not the negated direction",
        });
    }
    if frame.u.dot(frame.v).abs() > AXIS_TOLERANCE || frame.u.dot(frame.w).abs() > AXIS_TOLERANCE {
        return Err(SurrogateDefect::Frame {
            axis: "u",
            reason: "not orthogonal to v and w",
        });
    }
    if !close(frame.u.cross(frame.v), frame.w) {
        return Err(SurrogateDefect::Frame {
            axis: "v",
            reason: "not w x u (the frame is not right-handed)",
        });
    }
    Ok(())
}

fn validate_domain(domain: &Domain) -> Result<(), SurrogateDefect> {
    let (cols, rows) = (domain.cols, domain.rows);
    if !(2..=MAX_GRID).contains(&cols) || !(2..=MAX_GRID).contains(&rows) {
        return Err(SurrogateDefect::GridSize {
            cols,
            rows,
            max: MAX_GRID,
        });
    }
    let fields = [
        ("u_min", domain.u_min, false),
        ("v_min", domain.v_min, false),
        ("u_step", domain.u_step, true),
        ("v_step", domain.v_step, true),
    ];
    for (field, value, must_be_positive) in fields {
        if !value.is_finite() || (must_be_positive && value <= 0.0) {
            return Err(SurrogateDefect::Domain {
                field,
                value,
                must_be_positive,
            });
        }
    }
    Ok(())
}

fn validate_trim(trim: &TrimMask, domain: &Domain) -> Result<(), SurrogateDefect> {
    let (expected_s, expected_t) = (domain.cols - 1, domain.rows - 1);
    if (trim.cells_s, trim.cells_t) != (expected_s, expected_t) {
        return Err(SurrogateDefect::TrimShape {
            cells_s: trim.cells_s,
            cells_t: trim.cells_t,
            expected_s,
            expected_t,
        });
    }
    let expected = expected_s * expected_t;
    if trim.bits.len() != expected {
        return Err(SurrogateDefect::TrimLength {
            expected,
            got: trim.bits.len(),
        });
    }
    match trim.bits.iter().position(|&b| b & !ALL != 0) {
        Some(cell) => Err(SurrogateDefect::TrimBits {
            cell,
            bits: trim.bits[cell],
        }),
        None => Ok(()),
    }
}

fn validate_surface(
    slot: Side,
    safe: &SafeSurface,
    domain: &Domain,
    frame: &Frame,
) -> Result<(), SurrogateDefect> {
    let side = side_name(slot);
    if safe.side != slot {
        return Err(SurrogateDefect::SideMismatch {
            slot: side,
            found: side_name(safe.side),
        });
    }
    let surface = &safe.surface;
    if (surface.cols, surface.rows) != (domain.cols, domain.rows) {
        return Err(SurrogateDefect::SurfaceShape {
            side,
            cols: surface.cols,
            rows: surface.rows,
            domain_cols: domain.cols,
            domain_rows: domain.rows,
        });
    }
    let expected = domain.cols * domain.rows;
    if surface.coefficients.len() != expected {
        return Err(SurrogateDefect::CoefficientCount {
            side,
            expected,
            got: surface.coefficients.len(),
        });
    }
    if let Some(index) = surface.coefficients.iter().position(|c| !c.is_finite()) {
        return Err(SurrogateDefect::NonFiniteCoefficient {
            side,
            index,
            value: surface.coefficients[index],
        });
    }
    validate_certificate(slot, safe, frame)
}

fn validate_certificate(
    slot: Side,
    safe: &SafeSurface,
    frame: &Frame,
) -> Result<(), SurrogateDefect> {
    let side = side_name(slot);
    let certificate = &safe.certificate;
    let defect = |reason: String| Err(SurrogateDefect::Certificate { side, reason });
    if certificate.side != slot {
        return defect(format!("is for the {} side", side_name(certificate.side)));
    }
    if certificate.violations != 0 {
        return defect(format!(
            "records {} violations: the surface is not safe",
            certificate.violations
        ));
    }
    let gaps = [
        ("min_gap", certificate.min_gap),
        ("max_gap", certificate.max_gap),
        ("mean_gap", certificate.mean_gap),
    ];
    if let Some((name, value)) = gaps.iter().find(|(_, g)| !g.is_finite()) {
        return defect(format!("{name} is {value}, not a finite number"));
    }
    let direction = DVec3::from_array(certificate.direction);
    if !direction.is_finite() || (direction - frame.direction).length() > AXIS_TOLERANCE {
        return defect(format!(
            "direction {:?} differs from the frame direction",
            certificate.direction
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::samples::fitted;
    use crate::Sides;

    fn defect_after(edit: impl FnOnce(&mut Surrogate)) -> SurrogateDefect {
        let mut surrogate = fitted(Sides::Sandwich, true);
        edit(&mut surrogate);
        validate_surrogate(&surrogate).unwrap_err()
    }

    #[test]
    fn fitted_surrogates_are_valid() {
        for sides in [Sides::Upper, Sides::Lower, Sides::Sandwich] {
            assert_eq!(validate_surrogate(&fitted(sides, true)), Ok(()));
        }
    }

    #[test]
    fn non_finite_certificate_gaps_are_refused() {
        // Found by the surrogate_binary fuzz target: a binary surrogate with a
        // NaN gap was accepted, and its JSON (null) then refused.
        for value in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let defect = defect_after(|s| s.upper.as_mut().unwrap().certificate.mean_gap = value);
            assert!(
                matches!(&defect, SurrogateDefect::Certificate { side: "upper", reason } if reason.contains("mean_gap")),
                "{defect:?}"
            );
        }
    }

    #[test]
    fn every_broken_invariant_is_named() {
        assert_eq!(
            defect_after(|s| {
                s.upper = None;
                s.lower = None;
            }),
            SurrogateDefect::NoSurface
        );
        assert!(matches!(
            defect_after(|s| s.domain.u_step = 0.0),
            SurrogateDefect::Domain {
                field: "u_step",
                ..
            }
        ));
        assert!(matches!(
            defect_after(|s| s.domain.v_step = -1.0),
            SurrogateDefect::Domain {
                field: "v_step",
                ..
            }
        ));
        assert!(matches!(
            defect_after(|s| s.domain.u_min = f64::NAN),
            SurrogateDefect::Domain { field: "u_min", .. }
        ));
        assert!(matches!(
            defect_after(|s| s.domain.cols = 1),
            SurrogateDefect::GridSize { cols: 1, .. }
        ));
        assert!(matches!(
            defect_after(|s| s.frame.u *= 1.01),
            SurrogateDefect::Frame { axis: "u", .. }
        ));
        assert!(matches!(
            defect_after(|s| s.frame.v = -s.frame.v),
            SurrogateDefect::Frame { axis: "v", .. }
        ));
        assert!(matches!(
            defect_after(|s| s.frame.w.x = f64::INFINITY),
            SurrogateDefect::Frame { axis: "w", .. }
        ));
        assert!(matches!(
            defect_after(|s| s.trim.cells_s = 4),
            SurrogateDefect::TrimShape { cells_s: 4, .. }
        ));
        assert!(matches!(
            defect_after(|s| s.trim.bits.push(0)),
            SurrogateDefect::TrimLength {
                expected: 20,
                got: 21
            }
        ));
        assert!(matches!(
            defect_after(|s| s.trim.bits[3] = 0x10),
            SurrogateDefect::TrimBits {
                cell: 3,
                bits: 0x10
            }
        ));
        assert!(matches!(
            defect_after(|s| s.lower.as_mut().unwrap().side = Side::Upper),
            SurrogateDefect::SideMismatch {
                slot: "lower",
                found: "upper"
            }
        ));
        assert!(matches!(
            defect_after(|s| s.upper.as_mut().unwrap().surface.cols = 5),
            SurrogateDefect::SurfaceShape {
                side: "upper",
                cols: 5,
                ..
            }
        ));
        assert!(matches!(
            defect_after(|s| {
                s.upper.as_mut().unwrap().surface.coefficients.pop();
            }),
            SurrogateDefect::CoefficientCount {
                side: "upper",
                expected: 30,
                got: 29
            }
        ));
        assert!(matches!(
            defect_after(|s| s.lower.as_mut().unwrap().surface.coefficients[7] = f64::NAN),
            SurrogateDefect::NonFiniteCoefficient {
                side: "lower",
                index: 7,
                ..
            }
        ));
        assert!(matches!(
            defect_after(|s| s.upper.as_mut().unwrap().certificate.violations = 2),
            SurrogateDefect::Certificate { side: "upper", .. }
        ));
        assert!(matches!(
            defect_after(|s| s.lower.as_mut().unwrap().certificate.side = Side::Upper),
            SurrogateDefect::Certificate { side: "lower", .. }
        ));
        assert!(matches!(
            defect_after(|s| s.upper.as_mut().unwrap().certificate.direction[2] += 0.1),
            SurrogateDefect::Certificate { side: "upper", .. }
        ));
    }
}
