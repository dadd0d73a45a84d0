//! Surrogates on the wire: a [`Surrogate`] to its [`SurrogateMessage`] and back,
//! refusing on the way back anything a consumer should not trust (wrong
//! version, inconsistent grid, uncertified surface). The message type lives in
//! `shroud_msg`, which knows no splines; the conversion lives here.

use crate::{validate_surrogate, SafeSurface, Side, Surrogate, TrimMask};
use glam::DVec3;
use shroud_geometry::math::Frame;
use shroud_geometry::spline::UniformCubicSurface;
use shroud_msg::{
    bytes_to_f64s, f64s_to_bytes, CloudView, MessageError, SurfaceMessage, SurrogateMessage,
    SCHEMA_VERSION,
};

/// The conversions between a surrogate and its message.
pub trait SurrogateWire: Sized {
    /// The message of a fitted surrogate, with no field of view, no empty rays
    /// and no position error (the fit node sets those from the cloud).
    fn from_surrogate(
        s: &Surrogate,
        source_stamp_ns: u64,
        source_sequence: u64,
        source: &str,
        fit_ns: u64,
    ) -> Self;

    /// The message of `s` fitted to `cloud`, `since_ns` after the cloud's
    /// age was last counted (its transit to the fitter and its time there).
    /// It carries the cloud's stamp, sequence and source; its position error
    /// (the certificate is about the points as placed: the guard subtracts
    /// how far the sensor may have misplaced them); where its sensor looked
    /// and got no return (outside them the surface was not measured,
    /// whatever the interpolation says); and its age so far.
    fn of_cloud(s: &Surrogate, cloud: &CloudView<'_>, fit_ns: u64, since_ns: u64) -> Self;

    /// Decodes a message ([`SurrogateMessage::decode`]) and rebuilds the
    /// surrogate ([`SurrogateWire::to_surrogate`]).
    fn from_bytes(bytes: &[u8]) -> Result<(Self, Surrogate), MessageError>;

    /// Rebuilds the surrogate, refusing an inconsistent grid or a surface that
    /// breaks an invariant of [`validate_surrogate`].
    fn to_surrogate(&self) -> Result<Surrogate, MessageError>;
}

impl SurrogateWire for SurrogateMessage {
    fn from_surrogate(
        s: &Surrogate,
        source_stamp_ns: u64,
        source_sequence: u64,
        source: &str,
        fit_ns: u64,
    ) -> Self {
        let f = &s.frame;
        Self {
            version: SCHEMA_VERSION,
            source_stamp_ns,
            source_sequence,
            pipeline_ns: 0,
            source: source.to_owned(),
            direction: f.direction.to_array(),
            u: f.u.to_array(),
            v: f.v.to_array(),
            w: f.w.to_array(),
            domain: s.domain,
            cells_s: s.trim.cells_s,
            cells_t: s.trim.cells_t,
            trim: s.trim.bits.clone(),
            surfaces: s
                .surfaces()
                .map(|x| SurfaceMessage {
                    side: x.side,
                    coefficients: f64s_to_bytes(&x.surface.coefficients),
                    certificate: x.certificate.clone(),
                })
                .collect(),
            stats: s.stats.clone(),
            fit_ns,
            position_error_m: 0.0,
            field_of_view: None,
            no_return: None,
        }
    }

    fn of_cloud(s: &Surrogate, cloud: &CloudView<'_>, fit_ns: u64, since_ns: u64) -> Self {
        let mut msg =
            Self::from_surrogate(s, cloud.stamp_ns, cloud.sequence, &cloud.source, fit_ns);
        msg.position_error_m = cloud.position_error_m;
        msg.field_of_view = cloud.field_of_view;
        msg.no_return = cloud.no_return.clone();
        msg.pipeline_ns = cloud.pipeline_ns.saturating_add(since_ns);
        msg
    }

    fn from_bytes(bytes: &[u8]) -> Result<(Self, Surrogate), MessageError> {
        let msg = SurrogateMessage::decode(bytes)?;
        let surrogate = msg.to_surrogate()?;
        Ok((msg, surrogate))
    }

    fn to_surrogate(&self) -> Result<Surrogate, MessageError> {
        let frame = Frame {
            direction: DVec3::from_array(self.direction),
            u: DVec3::from_array(self.u),
            v: DVec3::from_array(self.v),
            w: DVec3::from_array(self.w),
        };
        let trim = TrimMask {
            cells_s: self.cells_s,
            cells_t: self.cells_t,
            bits: self.trim.clone(),
        };
        let mut surrogate = Surrogate {
            frame,
            domain: self.domain,
            trim,
            upper: None,
            lower: None,
            stats: self.stats.clone(),
        };
        for surface in &self.surfaces {
            let coefficients = bytes_to_f64s(&surface.coefficients, "coefficients")?;
            let expected = self.domain.cols.saturating_mul(self.domain.rows);
            if coefficients.len() != expected {
                return Err(MessageError::Count {
                    field: "coefficients",
                    found: coefficients.len(),
                    expected,
                });
            }
            let grid = UniformCubicSurface::new(self.domain.cols, self.domain.rows, coefficients)
                .ok_or_else(|| MessageError::Invalid {
                field: "domain",
                reason: "the grid must be at least 2 x 2".into(),
            })?;
            let safe = SafeSurface {
                side: surface.side,
                surface: grid,
                certificate: surface.certificate.clone(),
            };
            let slot = match surface.side {
                Side::Upper => &mut surrogate.upper,
                Side::Lower => &mut surrogate.lower,
            };
            if slot.replace(safe).is_some() {
                return Err(MessageError::Invalid {
                    field: "surfaces",
                    reason: "a side appears twice".into(),
                });
            }
        }
        validate_surrogate(&surrogate).map_err(|defect| MessageError::Invalid {
            field: "surrogate",
            reason: defect.to_string(),
        })?;
        Ok(surrogate)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{fit_surrogate, FitOptions, Sides};

    fn surrogate() -> Surrogate {
        let points: Vec<[f32; 3]> = (0..600)
            .map(|i| {
                let (x, y) = ((i % 30) as f32 * 0.1, (i / 30) as f32 * 0.1);
                [x, y, (x * 2.0).sin() * 0.3 + y * 0.1]
            })
            .collect();
        fit_surrogate(
            &points,
            &FitOptions {
                cols: 7,
                rows: 5,
                sides: Sides::Sandwich,
                ..Default::default()
            },
        )
        .unwrap()
    }

    #[test]
    fn round_trip_rebuilds_the_same_surrogate() {
        let s = surrogate();
        let msg = SurrogateMessage::from_surrogate(&s, 42, 3, "fit", 1500);
        let (back_msg, back) = SurrogateMessage::from_bytes(&msg.to_bytes().unwrap()).unwrap();
        assert_eq!(back_msg, msg);
        assert_eq!(back, s);
        // Coefficients are raw little-endian f64, row-major.
        let first = &msg.surfaces[0].coefficients[0..8];
        assert_eq!(
            first,
            &s.upper.as_ref().unwrap().surface.coefficients[0].to_le_bytes()
        );
    }

    #[test]
    fn a_surrogate_of_a_cloud_carries_its_stamps_its_view_and_its_age() {
        let s = surrogate();
        let points = [[0.0f32, 0.0, 0.0]];
        let fov = shroud_msg::sample_field_of_view();
        let cloud = CloudView::new(42, 3, "scan", shroud_msg::SensorPose::default(), &points)
            .with_pipeline_ns(1_000)
            .with_position_error_m(0.01)
            .unwrap()
            .with_field_of_view(fov)
            .unwrap();
        let msg = SurrogateMessage::of_cloud(&s, &cloud, 1500, 250);
        assert_eq!(
            (
                msg.source_stamp_ns,
                msg.source_sequence,
                msg.source.as_str()
            ),
            (42, 3, "scan")
        );
        assert_eq!((msg.fit_ns, msg.pipeline_ns), (1500, 1_250));
        assert_eq!(msg.position_error_m, 0.01);
        assert_eq!(msg.field_of_view, Some(fov));
        assert_eq!(msg.no_return, None);
        let saturated = CloudView::new(42, 3, "scan", shroud_msg::SensorPose::default(), &points)
            .with_pipeline_ns(u64::MAX);
        assert_eq!(
            SurrogateMessage::of_cloud(&s, &saturated, 1, 5).pipeline_ns,
            u64::MAX
        );
    }

    #[test]
    fn inconsistent_or_corrupted_messages_are_refused() {
        let s = surrogate();
        let good = SurrogateMessage::from_surrogate(&s, 42, 3, "fit", 1500);
        let mut msg = good.clone();
        msg.surfaces[0].coefficients.truncate(16);
        assert!(matches!(
            SurrogateMessage::from_bytes(&msg.to_bytes().unwrap()),
            Err(MessageError::Count { .. })
        ));
        let mut msg = good.clone();
        msg.surfaces[0].certificate.violations = 1;
        assert!(matches!(
            SurrogateMessage::from_bytes(&msg.to_bytes().unwrap()),
            Err(MessageError::Invalid { .. })
        ));
        let mut msg = good.clone();
        msg.trim.pop();
        assert!(SurrogateMessage::from_bytes(&msg.to_bytes().unwrap()).is_err());
        for bad in [f64::NAN, -0.1, f64::INFINITY] {
            let mut msg = good.clone();
            msg.position_error_m = bad;
            assert!(matches!(
                SurrogateMessage::from_bytes(&msg.to_bytes().unwrap()),
                Err(MessageError::Invalid {
                    field: "position_error_m",
                    ..
                })
            ));
        }
        let mut msg = good.clone();
        msg.field_of_view = Some(shroud_msg::sample_field_of_view());
        let (back, _) = SurrogateMessage::from_bytes(&msg.to_bytes().unwrap()).unwrap();
        assert_eq!(back.field_of_view, msg.field_of_view);
        msg.field_of_view = Some(shroud_msg::FieldOfView {
            axis: [0.0, 0.0, 0.5],
            ..shroud_msg::sample_field_of_view()
        });
        let e = SurrogateMessage::from_bytes(&msg.to_bytes().unwrap()).unwrap_err();
        assert!(e.to_string().contains("axis"), "{e}");
        let mut msg = good.clone();
        msg.no_return = Some(shroud_msg::sample_no_return());
        let (back, _) = SurrogateMessage::from_bytes(&msg.to_bytes().unwrap()).unwrap();
        assert_eq!(back.no_return, msg.no_return);
        msg.no_return.as_mut().unwrap().cones[1].half_angle = 2.0;
        let e = SurrogateMessage::from_bytes(&msg.to_bytes().unwrap()).unwrap_err();
        assert!(e.to_string().contains("no_return"), "{e}");
        let bytes = good.to_bytes().unwrap();
        for len in (0..bytes.len()).step_by(7) {
            assert!(SurrogateMessage::from_bytes(&bytes[..len]).is_err());
        }
    }
}
