//! Frames built through a DBC: values are clamped into what their signal can
//! carry (a radar reports a far target at its field's limit rather than not
//! at all), and signals the caller leaves out are sent as the in-range value
//! nearest zero, so that a DBC adding a reserved signal does not break the
//! emulator. A name the message lacks is still an error.

use shroud_drivers::can::CanFrame;
use shroud_drivers::dbc::{CanDatabase, DbcError, Multiplex, SignalSpec};

/// The frame of `message` carrying `values` (by signal name).
pub(crate) fn encode(
    db: &CanDatabase,
    message: &str,
    values: &[(&str, f64)],
) -> Result<CanFrame, DbcError> {
    let spec = db
        .message(message)
        .ok_or_else(|| DbcError::UnknownMessage(message.to_string()))?;
    let mut all: Vec<(&str, f64)> = Vec::with_capacity(spec.signals.len() + values.len());
    for signal in &spec.signals {
        if matches!(signal.multiplex, Multiplex::Multiplexed(_)) {
            continue;
        }
        let given = values.iter().rev().find(|(name, _)| *name == signal.name);
        let value = given.map_or(0.0, |(_, v)| *v);
        all.push((signal.name.as_str(), clamp(signal, value)));
    }
    // Names the message lacks go through unchanged: `encode` names them.
    all.extend(
        values
            .iter()
            .filter(|(name, _)| spec.signal(name).is_none())
            .copied(),
    );
    db.encode(message, &all)
}

/// `value` moved into the signal's range: the DBC's `[min|max]` when it gives
/// one, within what its bits hold. Not-a-number becomes the lower bound.
fn clamp(signal: &SignalSpec, value: f64) -> f64 {
    let (mut lo, mut hi) = signal.physical_bounds();
    if signal.has_range() {
        lo = lo.max(signal.min.min(signal.max));
        hi = hi.min(signal.min.max(signal.max));
    }
    if lo > hi {
        return lo;
    }
    let value = if value.is_nan() { lo } else { value };
    // Round to the raw step first, so that rounding cannot leave the range.
    let step = signal.factor.abs();
    let snapped = if step > 0.0 && step.is_finite() {
        ((value - signal.offset) / step).round() * step + signal.offset
    } else {
        value
    };
    let inside = |v: f64| v >= lo - step * 1e-6 && v <= hi + step * 1e-6;
    if inside(snapped) {
        snapped
    } else {
        value.clamp(lo, hi)
    }
}
