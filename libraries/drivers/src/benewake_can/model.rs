//! The Benewake CAN models and what differs between them: frame layout (by
//! their builtin DBC), default id, range limit and which readings are not
//! measurements (a [`Validity`], shared with the UART models).

pub use crate::benewake::Validity;

/// A Benewake rangefinder with a CAN interface (sensors.md §2.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum BenewakeCanModel {
    /// TF03-CAN: dist + strength, little-endian, standard id 0x003, no timestamp.
    Tf03,
    /// TFmini-i-CAN: dist + strength + u32 ms timestamp, little-endian,
    /// standard id 0x003.
    TfminiI,
    /// TF02-i-CAN: the TFmini-i layout, with the TF02 family's range.
    Tf02I,
    /// Legacy TF02 CAN: big-endian dist and strength, exposure time and
    /// reliability bytes, extended id 0x00090002.
    Tf02,
}

impl BenewakeCanModel {
    pub const ALL: [Self; 4] = [Self::Tf03, Self::TfminiI, Self::Tf02I, Self::Tf02];

    /// `tf03`, `tfmini-i`, `tf02-i`, `tf02` (also accepted by [`Self::from_name`]).
    pub fn name(self) -> &'static str {
        match self {
            Self::Tf03 => "tf03",
            Self::TfminiI => "tfmini-i",
            Self::Tf02I => "tf02-i",
            Self::Tf02 => "tf02",
        }
    }

    /// The model called `name` (any case).
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL
            .into_iter()
            .find(|m| m.name().eq_ignore_ascii_case(name))
    }

    /// The builtin DBC of the model's layout (`dbc::builtin`).
    pub fn dbc_name(self) -> &'static str {
        match self {
            Self::Tf03 => "benewake_tf03",
            Self::TfminiI | Self::Tf02I => "benewake_tfmini_i",
            Self::Tf02 => "benewake_tf02",
        }
    }

    /// The one message of that DBC.
    pub fn message_name(self) -> &'static str {
        match self {
            Self::Tf03 => "TF03_Measurement",
            Self::TfminiI | Self::Tf02I => "TFminiI_Measurement",
            Self::Tf02 => "TF02_Measurement",
        }
    }

    /// The factory send id and whether it is extended (sensors.md §2.1).
    pub fn default_id(self) -> (u32, bool) {
        match self {
            Self::Tf03 | Self::TfminiI | Self::Tf02I => (0x003, false),
            Self::Tf02 => (0x0009_0002, true),
        }
    }

    /// The bytes a data frame carries: 6 on the TF03 (TF03 manual V1.2.2
    /// p.12, Table 7: dist, strength, two reserved bytes), 8 on the others
    /// (TFmini-i manual §3.2 Table 4; TF02 manual V1.1 p.9 Table 5). A
    /// shorter frame is a `bad_frame`.
    pub fn dlc(self) -> u8 {
        match self {
            Self::Tf03 => 6,
            Self::TfminiI | Self::Tf02I | Self::Tf02 => 8,
        }
    }

    /// Whether the frame carries the device's u32 ms timestamp (bytes 4-7,
    /// TFmini-i manual §3.2 Table 4; the TF02-i shares it, TF02-i manual p.14).
    pub fn has_timestamp(self) -> bool {
        matches!(self, Self::TfminiI | Self::Tf02I)
    }

    /// The largest distance that is a measurement, in cm: TF03 180 m (the
    /// TF03-180's range; sensors.md has none, so this is the family's rule
    /// "beyond the maximum is out of range"), TFmini-i 12 m and TF02-i 40 m
    /// (as their UART siblings TFmini Plus and TF02-Pro, sensors.md §1.3),
    /// legacy TF02 below 22 m (its manual V1.1 p.8: an output of 22 m means
    /// out of range or too weak).
    pub fn max_range_cm(self) -> u32 {
        match self {
            // 18000 cm is the TF03's out-of-range code (its default "over
            // range threshold", TF03 manual V1.2.2 p.14), not a reading.
            Self::Tf03 => 17_999,
            Self::TfminiI => 1_200,
            Self::Tf02I => 4_000,
            Self::Tf02 => 2_199,
        }
    }

    /// What a reading is worth. The device's own verdicts come first
    /// (reliability, then strength), then the range check (0 or beyond
    /// [`Self::max_range_cm`] is out of range):
    ///
    /// - TF03: strength below 40 is too weak (TF03 manual V1.2.2 p.11, note 1:
    ///   "threshold of strength is 40").
    /// - TFmini-i-CAN: sensors.md documents no CAN rule; the family's
    ///   TFmini Plus rule applies (sensors.md §1.3, TFmini Plus manual p.13):
    ///   strength < 100 weak, 65535 saturated.
    /// - TF02-i-CAN: no CAN rule either; the family's TF02-Pro rule (sensors.md
    ///   §1.3, TF02-Pro manual p.9): strength < 60 weak (its distance then
    ///   reads 4500 cm, out of range too).
    /// - Legacy TF02: reliability (SIG, byte 5) other than 7 or 8 is not to be
    ///   used (TF02 manual V1.1 p.9, Table 5; sensors.md §2.1).
    pub fn verdict(self, distance_cm: u32, strength: u32, reliability: Option<u32>) -> Validity {
        let device = match self {
            Self::Tf02 => (!matches!(reliability, Some(7 | 8))).then_some(Validity::Unreliable),
            Self::Tf03 => (strength < 40).then_some(Validity::WeakReturn),
            Self::TfminiI => {
                if strength == 65_535 {
                    Some(Validity::Saturated)
                } else {
                    (strength < 100).then_some(Validity::WeakReturn)
                }
            }
            Self::Tf02I => (strength < 60).then_some(Validity::WeakReturn),
        };
        device.unwrap_or(if distance_cm == 0 || distance_cm > self.max_range_cm() {
            Validity::OutOfRange
        } else {
            Validity::Valid
        })
    }
}
