//! Whether a reading is a measurement, and if not, why: the verdict of the
//! models' rules ([`BenewakeModel::strength_verdict`]), carried by every
//! [`Reading`] and shared with the CAN models. A module of its own so that
//! both the models and the readings build on it.
//!
//! [`BenewakeModel::strength_verdict`]: super::BenewakeModel::strength_verdict
//! [`Reading`]: super::Reading

/// Whether a reading is a measurement, and if not, why.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Validity {
    /// A distance within the model's range and a usable strength.
    Valid,
    /// The strength is below the model's threshold: the distance word holds
    /// the model's invalid code (0xFFFF, 0, 4500) or an unreliable value.
    WeakReturn,
    /// The strength is 65535 (TFmini Plus, TF-Luna): the receiver is
    /// overexposed.
    Saturated,
    /// Distance 0, or at or beyond the model's out-of-range code or maximum
    /// range.
    OutOfRange,
    /// The device's own reliability byte says not to use it (the legacy
    /// TF02 on CAN).
    Unreliable,
}

impl Validity {
    /// The counter a reading of this kind is counted under (`weak_return`,
    /// `saturated`, `out_of_range`, `unreliable`), `None` for a valid one.
    pub fn counter(self) -> Option<&'static str> {
        match self {
            Self::Valid => None,
            Self::WeakReturn => Some("weak_return"),
            Self::Saturated => Some("saturated"),
            Self::OutOfRange => Some("out_of_range"),
            Self::Unreliable => Some("unreliable"),
        }
    }
}
