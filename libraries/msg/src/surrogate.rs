//! Surrogate messages: frame, domain, grid, coefficients (f64 blob), trim bits,
//! side, certificate, the source cloud's stamp and sequence, and fit statistics.

use super::blob::{decode, encode};
use super::error::MessageError;
use super::{check_version, FieldOfView, NoReturn, SCHEMA_VERSION};
use super::{Certificate, Domain, FitStats, Side};
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
    pub fn to_bytes(&self) -> Result<Vec<u8>, MessageError> {
        encode(self)
    }

    /// Decodes a message and checks what needs no geometry: the version, the
    /// position error, the field of view and the empty rays. Rebuilding and
    /// validating the surfaces is `shroud_surrogate::SurrogateWire::from_bytes`.
    pub fn decode(bytes: &[u8]) -> Result<Self, MessageError> {
        let msg: SurrogateMessage = decode(bytes)?;
        check_version("surrogate", msg.version, SCHEMA_VERSION)?;
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
        Ok(msg)
    }
}
