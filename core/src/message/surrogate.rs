//! Surrogate messages: frame, domain, grid, coefficients (f64 blob), trim bits,
//! side, certificate, the source cloud's stamp and sequence, and fit statistics.

use super::blob::{bytes_to_f64s, decode, encode, f64s_to_bytes};
use super::error::MessageError;
use super::{check_version, FieldOfView, NoReturn, SCHEMA_VERSION};
use crate::format::validate_surrogate;
use crate::math::Frame;
use crate::spline::UniformCubicSurface;
use crate::surrogate::{Certificate, Domain, FitStats, SafeSurface, Side, Surrogate, TrimMask};
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// One certified surface on the wire.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SurfaceMessage {
    pub side: Side,
    /// `cols * rows` little-endian f64, row-major (`b[k * cols + j]`).
    #[serde(with = "serde_bytes")]
    pub coefficients: Vec<u8>,
    pub certificate: Certificate,
}

/// A surrogate on the wire (MessagePack map with these field names).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SurrogateMessage {
    pub version: u16,
    /// Stamp and sequence of the cloud this surrogate certifies.
    pub source_stamp_ns: u64,
    pub source_sequence: u64,
    /// Time the source cloud had spent in shroud nodes when this surrogate was
    /// published: the cloud's own `pipeline_ns` plus the fit node's wait,
    /// decode and fit (up to the encoding), on the fit node's monotonic clock.
    pub pipeline_ns: u64,
    pub source: String,
    /// Frame axes: the fitting direction and `u`, `v`, `w` (each x, y, z).
    pub direction: [f64; 3],
    pub u: [f64; 3],
    pub v: [f64; 3],
    pub w: [f64; 3],
    pub domain: Domain,
    pub cells_s: usize,
    pub cells_t: usize,
    /// One byte per cell (`cells_s * cells_t`, row-major): triangle bits
    /// bottom 1, right 2, top 4, left 8.
    #[serde(with = "serde_bytes")]
    pub trim: Vec<u8>,
    pub surfaces: Vec<SurfaceMessage>,
    pub stats: FitStats,
    /// Wall time of the fit, nanoseconds.
    pub fit_ns: u64,
    /// Bound on how far any point of the source cloud may lie from where its
    /// sensor placed it (metres, finite, `>= 0`; the cloud's own bound, 0 when
    /// the sensor states none): the certificate is about the points as
    /// placed, so a consumer shrinks every clearance by this. Absent on the
    /// wire when 0, so a surrogate of an exact sensor encodes as before.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub position_error_m: f64,
    /// The region the source cloud's sensor covered, copied from the cloud
    /// (absent when the cloud had none): a consumer counts space outside it
    /// as unseen, since the surface over it was not measured.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub field_of_view: Option<FieldOfView>,
    /// The directions in which the source cloud's sensor got no return,
    /// copied from the cloud (absent when the cloud had none): a consumer
    /// counts them as unseen, since the surface across them was interpolated
    /// over whatever returned nothing.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub no_return: Option<NoReturn>,
}

fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

impl SurrogateMessage {
    pub fn from_surrogate(
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

    pub fn to_bytes(&self) -> Result<Vec<u8>, MessageError> {
        encode(self)
    }

    /// Decodes a message and rebuilds the surrogate, refusing anything a consumer
    /// should not trust (wrong version, inconsistent grid, uncertified surface).
    pub fn from_bytes(bytes: &[u8]) -> Result<(Self, Surrogate), MessageError> {
        let msg: SurrogateMessage = decode(bytes)?;
        check_version(msg.version)?;
        if !(msg.position_error_m.is_finite() && msg.position_error_m >= 0.0) {
            return Err(MessageError::Invalid {
                field: "position_error_m",
                reason: format!("{} is not a finite distance >= 0", msg.position_error_m),
            });
        }
        if let Some(fov) = &msg.field_of_view {
            fov.validate()?;
        }
        if let Some(no_return) = &msg.no_return {
            no_return.validate()?;
        }
        let surrogate = msg.to_surrogate()?;
        Ok((msg, surrogate))
    }

    pub fn to_surrogate(&self) -> Result<Surrogate, MessageError> {
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
    use crate::surrogate::{fit_surrogate, FitOptions, Sides};

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
        msg.field_of_view = Some(super::super::sample_field_of_view());
        let (back, _) = SurrogateMessage::from_bytes(&msg.to_bytes().unwrap()).unwrap();
        assert_eq!(back.field_of_view, msg.field_of_view);
        msg.field_of_view = Some(crate::message::FieldOfView {
            axis: [0.0, 0.0, 0.5],
            ..super::super::sample_field_of_view()
        });
        let e = SurrogateMessage::from_bytes(&msg.to_bytes().unwrap()).unwrap_err();
        assert!(e.to_string().contains("axis"), "{e}");
        let mut msg = good.clone();
        msg.no_return = Some(super::super::sample_no_return());
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
