//! The emulated Benewake CAN models (sensors.md §2.1) and what distinguishes
//! them: DBC message, default ids and bit rate, strength scale, the distance
//! an unreliable reading carries, range, and which `5A` commands they take.

/// An emulated Benewake rangefinder with a CAN interface.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum BenewakeCanModel {
    /// TF03-CAN: TX 0x003 / RX 0x3003, 1 Mbit/s, Dist + Strength LE.
    Tf03,
    /// TFmini-i-CAN: 0x003 both ways, 250 kbit/s, Dist + Strength + ms
    /// timestamp LE.
    TfminiI,
    /// TF02-i-CAN: as the TFmini-i-CAN, 40 m.
    Tf02I,
    /// The legacy TF02 CAN version: extended 0x00090002, 1 Mbit/s, Dist and
    /// Strength big-endian, exposure time, reliability.
    Tf02,
}

/// How a model's data frame is filled.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Layout {
    /// Dist, Strength.
    DistStrength,
    /// Dist, Strength, Timestamp (ms).
    Timestamped,
    /// Dist, Strength, ExposureTime, Reliability.
    Legacy,
}

/// Which configuration commands a model takes on its receive id.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Commands {
    /// TF03: 0x50 TX id, 0x51 RX id, 0x52 bit rate, 0x5D frame type, 0x11
    /// save, 0x10 factory reset.
    Tf03,
    /// TFmini-i / TF02-i: 0x51 (type, baud code, RX id, TX id), 0x11 save,
    /// 0x10 factory reset.
    Industrial,
    /// None documented (legacy TF02): every frame is ignored.
    None,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct CanModelSpec {
    pub name: &'static str,
    /// `shroud_drivers::dbc::builtin` name and the data message in it.
    pub dbc: &'static str,
    pub message: &'static str,
    pub layout: Layout,
    pub commands: Commands,
    pub default_id: u32,
    pub default_extended: bool,
    pub bitrate: u32,
    /// Readings per second of each unit.
    pub rate_hz: f64,
    /// Readings with strength below this are unreliable.
    pub min_strength: u16,
    pub max_strength: u16,
    /// Range at which a 10 %-reflectance target just reaches `min_strength`.
    pub range_at_10pct_m: f64,
    /// Rays are cast this far (the model's range).
    pub cast_range_m: f64,
    /// The Dist field of an unreliable reading, cm.
    pub invalid_cm: u16,
}

impl BenewakeCanModel {
    /// Every model, in [`CAN_MODELS`](crate::can_device::CAN_MODELS) order.
    pub const ALL: [BenewakeCanModel; 4] = [Self::Tf03, Self::TfminiI, Self::Tf02I, Self::Tf02];

    /// `tf03-can`, `tfmini-i-can`, `tf02-i-can` or `tf02-can`.
    pub fn name(self) -> &'static str {
        self.spec().name
    }

    /// The model called `name` (as [`Self::name`] spells it).
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name() == name)
    }

    /// The id a unit sends on out of the box.
    pub fn default_id(self) -> u32 {
        self.spec().default_id
    }

    /// Whether that id is extended (29-bit).
    pub fn default_extended(self) -> bool {
        self.spec().default_extended
    }

    /// The bus bit rate out of the box.
    pub fn bitrate(self) -> u32 {
        self.spec().bitrate
    }

    /// The Dist (cm) an unreliable reading carries.
    pub fn invalid_cm(self) -> u16 {
        self.spec().invalid_cm
    }

    /// Readings below this strength are unreliable.
    pub fn min_strength(self) -> u16 {
        self.spec().min_strength
    }

    /// Readings per second of each unit.
    pub fn rate_hz(self) -> f64 {
        self.spec().rate_hz
    }

    /// The id the unit listens on for `5A` commands, given the id it sends
    /// on: the TF03's default pair is TX 0x003 / RX 0x3003, so the emulator
    /// gives a unit sending on `id` the RX id 0x3000 + `id` (its assumption
    /// for non-default ids); the TFmini-i and TF02-i receive on their send id
    /// by default (manual §3.2.1: both 0x00000003).
    pub fn default_rx_id(self, tx_id: u32) -> u32 {
        match self.spec().commands {
            Commands::Tf03 => 0x3000u32.saturating_add(tx_id).min(MAX_EXTENDED_ID),
            _ => tx_id,
        }
    }

    pub(crate) fn spec(self) -> &'static CanModelSpec {
        match self {
            Self::Tf03 => &TF03,
            Self::TfminiI => &TFMINI_I,
            Self::Tf02I => &TF02_I,
            Self::Tf02 => &TF02,
        }
    }
}

const MAX_EXTENDED_ID: u32 = 0x1FFF_FFFF;

/// TF03 UART/CAN manual V1.2.2: strength 0–3500, threshold 40 (p.11); the
/// over-range threshold, 18000 cm by default (command table, p.14), is what
/// an out-of-range reading reads; 180 m (TF03-180), 70 m at 10 %; 100 Hz.
const TF03: CanModelSpec = CanModelSpec {
    name: "tf03-can",
    dbc: "benewake_tf03",
    message: "TF03_Measurement",
    layout: Layout::DistStrength,
    commands: Commands::Tf03,
    default_id: 0x003,
    default_extended: false,
    bitrate: 1_000_000,
    rate_hz: 100.0,
    min_strength: 40,
    max_strength: 3500,
    range_at_10pct_m: 70.0,
    cast_range_m: 180.0,
    invalid_cm: 18000,
};

/// TFmini-i-CAN (SJ-PM-TFmini-i A01 §3.2): 250 kbit/s, 0x003. Its manual
/// gives no invalid-reading rule; the emulator uses its UART sibling's, the
/// TFmini Plus (sensors.md §1.3, as in `shroud_drivers::benewake`):
/// Dist 0 when strength < 100; 12 m.
const TFMINI_I: CanModelSpec = CanModelSpec {
    name: "tfmini-i-can",
    dbc: "benewake_tfmini_i",
    message: "TFminiI_Measurement",
    layout: Layout::Timestamped,
    commands: Commands::Industrial,
    default_id: 0x003,
    default_extended: false,
    bitrate: 250_000,
    rate_hz: 100.0,
    min_strength: 100,
    max_strength: u16::MAX,
    range_at_10pct_m: 4.5,
    cast_range_m: 12.0,
    invalid_cm: 0,
};

/// TF02-i-CAN: as the TFmini-i-CAN; invalid readings follow its UART
/// sibling the TF02-Pro (sensors.md §1.3): Dist 4500 when strength < 60;
/// 40 m, 13.5 m at 10 %.
const TF02_I: CanModelSpec = CanModelSpec {
    name: "tf02-i-can",
    dbc: "benewake_tfmini_i",
    message: "TFminiI_Measurement",
    layout: Layout::Timestamped,
    commands: Commands::Industrial,
    default_id: 0x003,
    default_extended: false,
    bitrate: 250_000,
    rate_hz: 100.0,
    min_strength: 60,
    max_strength: u16::MAX,
    range_at_10pct_m: 13.5,
    cast_range_m: 40.0,
    invalid_cm: 4500,
};

/// Legacy TF02 CAN (TF02 manual V1.1 §4.2, data sheet SJ-GU-TF02-02 §9.4):
/// extended 0x00090002, 1 Mbit/s; 22 m; "if the output distance is 22 m, it
/// indicates out of range or insufficient signal strength", reliability 7 or
/// 8 = reliable. Its strength threshold is not given: the emulator uses 60.
const TF02: CanModelSpec = CanModelSpec {
    name: "tf02-can",
    dbc: "benewake_tf02",
    message: "TF02_Measurement",
    layout: Layout::Legacy,
    commands: Commands::None,
    default_id: 0x0009_0002,
    default_extended: true,
    bitrate: 1_000_000,
    rate_hz: 100.0,
    min_strength: 60,
    max_strength: 3000,
    range_at_10pct_m: 8.0,
    cast_range_m: 22.0,
    invalid_cm: 2200,
};
