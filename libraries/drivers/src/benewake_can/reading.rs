//! One rangefinder frame read through its model's DBC message (whatever id
//! the sensor was given) and judged by the model's rules.

use super::error::BenewakeCanError;
use super::model::{BenewakeCanModel, Validity};
use crate::can::CanFrame;
use crate::dbc::{builtin, MessageSpec};

/// The device's ms timestamp is published modulo 2^24 ms (4.66 hours) so that
/// every value is exact in the f32 of a cloud channel; the wrap is the
/// consumer's to unwrap (differences stay exact modulo 2^24).
pub const DEVICE_TIME_MODULUS_MS: u32 = 1 << 24;

/// One reading, decoded and judged.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CanReading {
    pub distance_cm: u32,
    pub strength: u32,
    /// The device's ms counter (TFmini-i, TF02-i).
    pub timestamp_ms: Option<u32>,
    /// Legacy TF02: exposure time (larger = longer) and reliability 1..8.
    pub exposure: Option<u32>,
    pub reliability: Option<u32>,
    pub validity: Validity,
    /// Metres when valid, else `NaN`.
    pub range_m: f32,
}

/// A model's message with the positions of its signals.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct ModelDecoder {
    model: BenewakeCanModel,
    spec: MessageSpec,
    distance: usize,
    strength: usize,
    timestamp: Option<usize>,
    exposure: Option<usize>,
    reliability: Option<usize>,
}

impl ModelDecoder {
    /// From the model's builtin DBC; fails if it lacks the message or a
    /// signal the model's rules need.
    pub fn new(model: BenewakeCanModel) -> Result<Self, BenewakeCanError> {
        let database_name = model.dbc_name();
        let database =
            builtin(database_name).ok_or(BenewakeCanError::MissingDatabase(database_name))?;
        let message = model.message_name();
        let spec = database
            .message(message)
            .ok_or(BenewakeCanError::MissingMessage {
                database: database_name,
                message,
            })?
            .clone();
        let find = |signal: &'static str| {
            spec.signal_index(signal)
                .ok_or(BenewakeCanError::MissingSignal { message, signal })
        };
        let distance = find("Dist")?;
        let strength = find("Strength")?;
        let timestamp = model
            .has_timestamp()
            .then(|| find("Timestamp"))
            .transpose()?;
        let legacy = model == BenewakeCanModel::Tf02;
        let exposure = legacy.then(|| find("ExposureTime")).transpose()?;
        let reliability = legacy.then(|| find("Reliability")).transpose()?;
        Ok(Self {
            model,
            spec,
            distance,
            strength,
            timestamp,
            exposure,
            reliability,
        })
    }

    /// The reading `frame` carries; `None` for a frame shorter than the
    /// model's DLC, a remote frame, or values that are not whole numbers.
    /// The TF03 sends 6 bytes where the DBC message has 8: the frame is
    /// decoded as if the reserved bytes were sent as 0 (no signal lies there).
    pub fn decode(&self, frame: &CanFrame) -> Option<CanReading> {
        if frame.remote || frame.len < self.model.dlc() {
            return None;
        }
        let mut data = [0u8; 8];
        for (to, from) in data.iter_mut().zip(frame.payload()) {
            *to = *from;
        }
        let padded = CanFrame {
            len: frame.len.max(self.spec.len).min(8),
            data,
            ..*frame
        };
        let decoded = self.spec.decode(&padded).ok()?;
        let get = |index: usize| decoded.value(index).and_then(whole);
        let at = |index: Option<usize>| match index {
            None => Some(None),
            Some(i) => get(i).map(Some),
        };
        let distance_cm = get(self.distance)?;
        let strength = get(self.strength)?;
        let timestamp_ms = at(self.timestamp)?;
        let exposure = at(self.exposure)?;
        let reliability = at(self.reliability)?;
        let validity = self.model.verdict(distance_cm, strength, reliability);
        let range_m = match validity {
            Validity::Valid => distance_cm as f32 / 100.0,
            _ => f32::NAN,
        };
        Some(CanReading {
            distance_cm,
            strength,
            timestamp_ms,
            exposure,
            reliability,
            validity,
            range_m,
        })
    }
}

fn whole(value: f64) -> Option<u32> {
    let fits = value.is_finite() && value >= 0.0 && value <= f64::from(u32::MAX);
    (fits && value.fract() == 0.0).then_some(value as u32)
}
