//! The emulated Benewake models and what distinguishes them: strength
//! scale, invalid-reading rule, range, frame-rate limit, command support.

/// An emulated Benewake UART rangefinder.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum BenewakeModel {
    /// The original TFmini (2017): strength 0–3000, byte 6 = distance mode,
    /// no `5A` command set.
    Tfmini,
    /// TFmini-S: distance −1 (0xFFFF) when strength < 100.
    TfminiS,
    /// TFmini Plus: distance 0 when strength < 100 or = 65535.
    TfminiPlus,
    /// TF-Luna: distance 0 when amp < 100 or = 65535; ignores command
    /// checksums unless told to check them.
    TfLuna,
    /// TF02-Pro: distance 4500 cm when strength < 60.
    Tf02Pro,
}

impl BenewakeModel {
    /// Every model, in name order.
    pub const ALL: [BenewakeModel; 5] = [
        BenewakeModel::Tfmini,
        BenewakeModel::TfminiS,
        BenewakeModel::TfminiPlus,
        BenewakeModel::TfLuna,
        BenewakeModel::Tf02Pro,
    ];

    /// `tfmini`, `tfmini-s`, `tfmini-plus`, `tf-luna` or `tf02-pro`.
    pub fn name(self) -> &'static str {
        self.spec().name
    }

    /// The model called `name` (as [`BenewakeModel::name`] spells it).
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|model| model.name() == name)
    }

    pub(crate) fn spec(self) -> &'static ModelSpec {
        match self {
            BenewakeModel::Tfmini => &TFMINI,
            BenewakeModel::TfminiS => &TFMINI_S,
            BenewakeModel::TfminiPlus => &TFMINI_PLUS,
            BenewakeModel::TfLuna => &TF_LUNA,
            BenewakeModel::Tf02Pro => &TF02_PRO,
        }
    }
}

/// What a model outputs when its reading is unreliable.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct InvalidRule {
    /// Readings with strength below this are unreliable.
    pub min_strength: u16,
    /// A strength of 65535 (overexposure) is unreliable too.
    pub saturation_invalid: bool,
    /// The distance field of an unreliable reading (any unit).
    pub distance: u16,
}

/// What bytes 6 and 7 of a frame hold.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum TailBytes {
    /// Chip temperature, raw = (°C + 256) × 8, u16 LE.
    Temperature,
    /// The original TFmini: distance mode (0x02 short, 0x07 long), then 0x00
    /// (SJ-PM-TFmini A03 manual, Table 6).
    DistanceMode,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ModelSpec {
    pub name: &'static str,
    /// Answers the `5A len id … sum` command set.
    pub has_commands: bool,
    /// Checks command sums from power-up (TF-Luna does not, until ID 0x08
    /// enables it: TF-Luna manual, ID_CHECKSUM).
    pub checks_sums: bool,
    /// Accepts ID 0x08, the checksum switch (TF-Luna only).
    pub checksum_switch: bool,
    pub tail: TailBytes,
    pub invalid: InvalidRule,
    /// Largest strength the model reports.
    pub max_strength: u16,
    /// Range at which a 10 %-reflectance target just reaches
    /// `invalid.min_strength` (the datasheets' "@10 %" range).
    pub range_at_10pct_m: f64,
    /// Rays are cast this far.
    pub cast_range_m: f64,
    /// Largest distance output, in cm; valid readings beyond saturate here.
    pub max_output_cm: u16,
    pub max_frame_rate_hz: u16,
    /// Reply to ID 0x01: V1, V2, V3 for version V3.V2.V1.
    pub version: [u8; 3],
}

/// TFmini: strength 0–3000, reliable from 20; beyond 12 m a reliable
/// reading reads 1200 cm; unreliable ones 0xFFFF (A03 manual §5.4).
const TFMINI: ModelSpec = ModelSpec {
    name: "tfmini",
    has_commands: false,
    checks_sums: true,
    checksum_switch: false,
    tail: TailBytes::DistanceMode,
    invalid: InvalidRule {
        min_strength: 20,
        saturation_invalid: false,
        distance: 0xFFFF,
    },
    max_strength: 3000,
    range_at_10pct_m: 5.0,
    cast_range_m: 18.0,
    max_output_cm: 1200,
    max_frame_rate_hz: 100,
    version: [0, 0, 0],
};

/// TFmini-S: 0.1–12 m, strength < 100 → −1 (A01 manual §5.4, Table 8).
const TFMINI_S: ModelSpec = ModelSpec {
    name: "tfmini-s",
    has_commands: true,
    checks_sums: true,
    checksum_switch: false,
    tail: TailBytes::Temperature,
    invalid: InvalidRule {
        min_strength: 100,
        saturation_invalid: false,
        distance: 0xFFFF,
    },
    max_strength: u16::MAX,
    range_at_10pct_m: 4.5,
    cast_range_m: 18.0,
    max_output_cm: 1200,
    max_frame_rate_hz: 1000,
    version: [3, 1, 2],
};

/// TFmini Plus: 0.1–12 m, strength < 100 or = 65535 → 0 (manual §5.4).
const TFMINI_PLUS: ModelSpec = ModelSpec {
    name: "tfmini-plus",
    has_commands: true,
    checks_sums: true,
    checksum_switch: false,
    tail: TailBytes::Temperature,
    invalid: InvalidRule {
        min_strength: 100,
        saturation_invalid: true,
        distance: 0,
    },
    max_strength: u16::MAX,
    range_at_10pct_m: 4.5,
    cast_range_m: 18.0,
    max_output_cm: 1200,
    max_frame_rate_hz: 1000,
    version: [6, 0, 2],
};

/// TF-Luna: 0.2–8 m, amp < 100 or = 65535 → dummy distance 0, output
/// limited to 900 cm, at most 250 Hz (A05 manual §6.4, §6.5, §6.8, §6.9).
const TF_LUNA: ModelSpec = ModelSpec {
    name: "tf-luna",
    has_commands: true,
    checks_sums: false,
    checksum_switch: true,
    tail: TailBytes::Temperature,
    invalid: InvalidRule {
        min_strength: 100,
        saturation_invalid: true,
        distance: 0,
    },
    max_strength: u16::MAX,
    range_at_10pct_m: 2.5,
    cast_range_m: 12.0,
    max_output_cm: 900,
    max_frame_rate_hz: 250,
    version: [0, 3, 3],
};

/// TF02-Pro: 0.1–40 m, strength < 60 → 4500 cm.
const TF02_PRO: ModelSpec = ModelSpec {
    name: "tf02-pro",
    has_commands: true,
    checks_sums: true,
    checksum_switch: false,
    tail: TailBytes::Temperature,
    invalid: InvalidRule {
        min_strength: 60,
        saturation_invalid: false,
        distance: 4500,
    },
    max_strength: u16::MAX,
    range_at_10pct_m: 13.5,
    cast_range_m: 60.0,
    max_output_cm: 4000,
    max_frame_rate_hz: 1000,
    version: [7, 4, 3],
};
