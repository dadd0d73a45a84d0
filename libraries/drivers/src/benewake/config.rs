//! What the integrator chooses about a Benewake device: model, line speed,
//! frame rate, output unit, whether to save, and the timeouts.

use std::time::Duration;

use super::model::BenewakeModel;

/// The unit of the distance word of a data frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum DistanceUnit {
    /// Centimetres: every model's factory default (output format `01`).
    #[default]
    Centimetre,
    /// Millimetres (output format `06`, TFmini-S and TFmini Plus only).
    Millimetre,
}

impl DistanceUnit {
    /// Device units in one metre.
    pub fn per_metre(self) -> f32 {
        match self {
            Self::Centimetre => 100.0,
            Self::Millimetre => 1000.0,
        }
    }

    /// The output-format code of command `05` selecting the standard 9-byte
    /// frame in this unit (TFmini-S manual Table 12: `01` cm, `06` mm).
    pub fn format_code(self) -> u8 {
        match self {
            Self::Centimetre => 0x01,
            Self::Millimetre => 0x06,
        }
    }

    /// `cm` or `mm`.
    pub fn symbol(self) -> &'static str {
        match self {
            Self::Centimetre => "cm",
            Self::Millimetre => "mm",
        }
    }
}

/// How to run one Benewake device.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BenewakeConfig {
    /// Which model is on the port: decides the invalid-reading rules, the
    /// range limit and whether commands are sent. Default `TfminiPlus`.
    pub model: BenewakeModel,
    /// The port's line speed (the driver asks for it with `SetBaud` at every
    /// connect and back-dates stamps by a frame's time on the wire at this
    /// rate). The driver never changes the device's own baud. Default 115200.
    pub baud: u32,
    /// Frame rate to set, in Hz; `Some(0)` selects trigger mode, where the
    /// driver triggers each reading itself. `None` (default) leaves the
    /// device's rate as it is.
    pub frame_rate: Option<u16>,
    /// Output unit to select. Default `Centimetre`. `Millimetre` is honoured
    /// only on models that support it ([`BenewakeModel::supports_mm_output`]);
    /// others stay in cm.
    pub unit: DistanceUnit,
    /// Send "save settings" (`5A 04 11 6F`) after configuring, which writes
    /// the device's flash. Default false.
    pub save: bool,
    /// How long to wait for the reply to each command. Default 500 ms.
    pub reply_timeout: Duration,
    /// The floor of the silence that makes the driver ask for a reconnect:
    /// the stream is declared dead after max(10 frame periods, this) without a
    /// data frame (in trigger mode, at least 2 × `reply_timeout`). Default
    /// 300 ms.
    pub stream_timeout: Duration,
    /// The longest a frame may wait where the host cannot see it: from its
    /// measurement to its first byte on the wire (the manuals state no such
    /// latency), plus from its last byte's arrival to its being readable (a
    /// USB-serial adapter's buffering: an FTDI adapter's latency timer is
    /// 16 ms by default). It widens every reading's time bound. Default 5 ms.
    pub link_latency: Duration,
}

impl Default for BenewakeConfig {
    fn default() -> Self {
        Self {
            model: BenewakeModel::TfminiPlus,
            baud: 115_200,
            frame_rate: None,
            unit: DistanceUnit::Centimetre,
            save: false,
            reply_timeout: Duration::from_millis(500),
            stream_timeout: Duration::from_millis(300),
            link_latency: Duration::from_millis(5),
        }
    }
}

impl BenewakeConfig {
    /// The unit the driver will select: the configured one if the model
    /// supports it, cm otherwise.
    pub fn effective_unit(&self) -> DistanceUnit {
        if self.model.supports_mm_output() {
            self.unit
        } else {
            DistanceUnit::Centimetre
        }
    }

    /// Whether the driver will set trigger mode and trigger every reading.
    pub fn trigger_mode(&self) -> bool {
        self.model.has_commands() && self.frame_rate == Some(0)
    }
}
