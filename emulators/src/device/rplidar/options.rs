//! How an emulated RPLIDAR is configured: its faults, health, noise and
//! seed.

use crate::device::Faults;

/// What GET_HEALTH reports (`sl_lidar_response_device_health_t`: status
/// 0 ok, 1 warning, 2 error, and a u16 error code).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum RplidarHealth {
    /// Status 0, error code 0.
    #[default]
    Ok,
    /// Status 1 with this error code; the device still scans.
    Warning(u16),
    /// Status 2 with this error code: the device is in Protection Stop and
    /// ignores SCAN, FORCE_SCAN and EXPRESS_SCAN (protocol PDF §3, "Protection
    /// Stop"); RESET does not clear an emulated error.
    Error(u16),
}

impl RplidarHealth {
    pub(crate) fn status_byte(self) -> u8 {
        match self {
            RplidarHealth::Ok => 0,
            RplidarHealth::Warning(_) => 1,
            RplidarHealth::Error(_) => 2,
        }
    }

    pub(crate) fn error_code(self) -> u16 {
        match self {
            RplidarHealth::Ok => 0,
            RplidarHealth::Warning(code) | RplidarHealth::Error(code) => code,
        }
    }

    pub(crate) fn blocks_scanning(self) -> bool {
        matches!(self, RplidarHealth::Error(_))
    }
}

/// Options of an [`RplidarEmulator`](super::RplidarEmulator).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RplidarOptions {
    /// `corrupt_every` = n: every n-th answer packet is damaged (a capsule's
    /// checksum, or a standard node's check bit cleared); `garbage_every` =
    /// n: 1–16 random bytes go out before every n-th answer packet, drawn
    /// from `faults.seed`.
    pub faults: Faults,
    /// What GET_HEALTH reports. Default ok.
    pub health: RplidarHealth,
    /// Seed of the range noise, the dropouts and the serial number.
    /// Default 0.
    pub seed: u64,
    /// Standard deviation of the range noise as a fraction of the range.
    /// Default 0.01.
    pub noise: f64,
    /// Probability that a sample is lost (distance 0, quality 0).
    /// Default 0.01.
    pub dropout: f64,
    /// Model the triangulation parallax: a sample's direction lies behind the
    /// encoder angle by atan(0.02 m / range) (at most 7.875°, the largest
    /// 6-bit dθ), which express capsules carry as their dθ offsets and
    /// standard nodes fold into their angle. Dense capsules carry no offset,
    /// so their samples lie on the encoder angle either way. Default true.
    pub angle_compensation: bool,
}

impl Default for RplidarOptions {
    fn default() -> Self {
        Self {
            faults: Faults::default(),
            health: RplidarHealth::Ok,
            seed: 0,
            noise: 0.01,
            dropout: 0.01,
            angle_compensation: true,
        }
    }
}
