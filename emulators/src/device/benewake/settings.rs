//! The rangefinder's configurable parameters, their factory values, and the
//! values the commands accept.

use super::model::ModelSpec;

/// Factory frame rate, Hz (all manuals: 100 Hz default).
pub(crate) const FACTORY_FRAME_RATE_HZ: u16 = 100;
/// Factory UART rate (all manuals: 115200 8N1).
pub(crate) const FACTORY_BAUD: u32 = 115_200;

/// UART rates the baud command accepts: the "standard baud rates" the
/// TFmini-S manual (Table 12, note ②) allows.
const STANDARD_BAUDS: [u32; 14] = [
    9_600, 14_400, 19_200, 38_400, 56_000, 57_600, 115_200, 128_000, 230_400, 256_000, 460_800,
    512_000, 750_000, 921_600,
];

/// How readings are sent (ID 0x05 values: 01 9-byte/cm, 02 Pix string, 06
/// 9-byte/mm; TFmini-S A01 manual Table 12).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum OutputFormat {
    Centimetres,
    Pix,
    Millimetres,
}

impl OutputFormat {
    pub(crate) fn from_id(format: u8) -> Option<Self> {
        match format {
            0x01 => Some(OutputFormat::Centimetres),
            0x02 => Some(OutputFormat::Pix),
            0x06 => Some(OutputFormat::Millimetres),
            _ => None,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Settings {
    /// 0 = trigger mode.
    pub frame_rate_hz: u16,
    pub format: OutputFormat,
    pub baud: u32,
    pub output_enabled: bool,
    /// Command sums are checked (always on but for a TF-Luna told otherwise).
    pub check_sums: bool,
}

impl Settings {
    pub(crate) fn factory(spec: &ModelSpec) -> Self {
        Self {
            frame_rate_hz: FACTORY_FRAME_RATE_HZ,
            format: OutputFormat::Centimetres,
            baud: FACTORY_BAUD,
            output_enabled: true,
            check_sums: spec.checks_sums,
        }
    }

    /// Seconds between frames, or `None` in trigger mode. Rates above the
    /// model's limit run at the limit.
    pub(crate) fn frame_period_s(&self, spec: &ModelSpec) -> Option<f64> {
        let rate = self.frame_rate_hz.min(spec.max_frame_rate_hz);
        (rate > 0).then(|| 1.0 / f64::from(rate))
    }
}

pub(crate) fn is_standard_baud(baud: u32) -> bool {
    STANDARD_BAUDS.contains(&baud)
}
