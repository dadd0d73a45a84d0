//! The models of the family and what differs between them: range limits,
//! which strengths make a distance meaningless, and whether the device takes
//! `5A` commands at all.

use super::validity::Validity;

/// A Benewake single-beam lidar speaking the 9-byte UART frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum BenewakeModel {
    /// The original TFmini (2017): no `5A` command interface, bytes 6/7 are
    /// distance mode / reserved instead of a temperature.
    Tfmini,
    /// TFmini-S.
    TfminiS,
    /// TFmini Plus.
    #[default]
    TfminiPlus,
    /// TF-Luna (its strength is called `Amp`).
    TfLuna,
    /// TF02-Pro.
    Tf02Pro,
}

impl BenewakeModel {
    /// Every model, in declaration order.
    pub const ALL: [BenewakeModel; 5] = [
        Self::Tfmini,
        Self::TfminiS,
        Self::TfminiPlus,
        Self::TfLuna,
        Self::Tf02Pro,
    ];

    /// A stable lower-case name (`tfmini`, `tfmini-s`, `tfmini-plus`,
    /// `tf-luna`, `tf02-pro`), also accepted by [`Self::from_name`].
    pub fn name(self) -> &'static str {
        match self {
            Self::Tfmini => "tfmini",
            Self::TfminiS => "tfmini-s",
            Self::TfminiPlus => "tfmini-plus",
            Self::TfLuna => "tf-luna",
            Self::Tf02Pro => "tf02-pro",
        }
    }

    /// The model called `name` (as [`Self::name`] spells it, any case).
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL
            .into_iter()
            .find(|model| model.name().eq_ignore_ascii_case(name))
    }

    /// The datasheet's maximum range, in cm: 12 m for the TFmini, TFmini-S
    /// and TFmini Plus (ArduPilot `AP_RangeFinder_Benewake_TFMini.h`:
    /// `model_dist_max_cm() = 1200`), 8 m for the TF-Luna, 40 m for the
    /// TF02-Pro (their datasheets, 90 % reflectivity).
    pub fn max_range_cm(self) -> u16 {
        match self {
            Self::Tfmini | Self::TfminiS | Self::TfminiPlus => 1200,
            Self::TfLuna => 800,
            Self::Tf02Pro => 4000,
        }
    }

    /// The output rate a device leaves the factory with, Hz: 100 for every
    /// model (the manuals' frame-rate command, ID 0x03, "default 100 Hz";
    /// TF-Luna manual §5.5; the original TFmini's datasheet gives 100 Hz).
    /// A device whose saved rate differs must be configured with its rate,
    /// or its readings' time bounds are wrong.
    pub fn factory_frame_rate_hz(self) -> u16 {
        100
    }

    /// Whether the device takes `5A` command frames (all but the original
    /// TFmini, whose 2017 datasheet documents none).
    pub fn has_commands(self) -> bool {
        self != Self::Tfmini
    }

    /// Whether bytes 6-7 of a data frame are the chip temperature.
    pub fn has_temperature(self) -> bool {
        self != Self::Tfmini
    }

    /// Whether the driver may select the 9-byte/mm output format (`5A 05 05
    /// 06`): documented for the TFmini-S and TFmini Plus (sensors.md §1.3). The
    /// TF-Luna has a mm format under an id sensors.md does not confirm, so it
    /// is not used.
    pub fn supports_mm_output(self) -> bool {
        matches!(self, Self::TfminiS | Self::TfminiPlus)
    }

    /// What the strength alone says about the reading, per the model's manual
    /// (sensors.md §1.3): `None` when it does not invalidate it.
    ///
    /// - TFmini-S: distance is -1 (0xFFFF) when strength < 100.
    /// - TFmini Plus: distance is 0 when strength < 100 or strength == 65535.
    /// - TF02-Pro: distance is 4500 when strength < 60.
    /// - TF-Luna: unreliable when Amp < 100 or Amp == 65535 (overexposed).
    /// - Original TFmini: no documented strength rule.
    pub fn strength_verdict(self, strength: u16) -> Option<Validity> {
        let (weak_below, saturates) = match self {
            Self::Tfmini => return None,
            Self::TfminiS => (100, false),
            Self::TfminiPlus | Self::TfLuna => (100, true),
            Self::Tf02Pro => (60, false),
        };
        if saturates && strength == u16::MAX {
            Some(Validity::Saturated)
        } else if strength < weak_below {
            Some(Validity::WeakReturn)
        } else {
            None
        }
    }
}
