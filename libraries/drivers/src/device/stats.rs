//! What a driver counts: bytes, scans, commands, and every rejected input or
//! device fault by a named kind, so a node can publish them in its status.

use std::collections::BTreeMap;
use std::fmt;

/// Counters of one driver, kept across reconnects.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct DeviceStats {
    /// Bytes handed to the driver.
    pub bytes: u64,
    /// Complete scans delivered.
    pub scans: u64,
    /// Commands written to the device.
    pub commands: u64,
    /// Handshakes completed (the first connect and every reconnect).
    pub handshakes: u64,
    /// Reconnects the driver asked for.
    pub reconnects: u64,
    /// Errors and faults by kind (`bad_checksum`, `garbage`, `timeout`,
    /// `incomplete_scan`, `device_error`, ...): snake_case names, stable,
    /// published as `<kind>` counters in the node's status.
    errors: BTreeMap<&'static str, u64>,
    /// Readings the device itself marked invalid (too weak, saturated, out
    /// of range), by kind: not errors (the input was sound), delivered as
    /// `NaN` rays.
    invalid_readings: BTreeMap<&'static str, u64>,
    /// Input dropped by design, not because it was wrong (the partial first
    /// revolution after a start, frames that arrive while configuring, an
    /// optional query a model does not answer), by kind.
    notes: BTreeMap<&'static str, u64>,
}

impl DeviceStats {
    /// Counts one error of `kind`.
    pub fn count(&mut self, kind: &'static str) {
        self.add(kind, 1);
    }

    /// Counts `n` errors of `kind`.
    pub fn add(&mut self, kind: &'static str, n: u64) {
        if n > 0 {
            *self.errors.entry(kind).or_default() += n;
        }
    }

    /// Errors of `kind` so far.
    pub fn errors(&self, kind: &str) -> u64 {
        self.errors.get(kind).copied().unwrap_or(0)
    }

    /// Every non-zero error counter, by name.
    pub fn error_counts(&self) -> impl Iterator<Item = (&'static str, u64)> + '_ {
        self.errors.iter().map(|(k, v)| (*k, *v))
    }

    /// Counts one reading the device marked invalid, of `kind`.
    pub fn count_invalid_reading(&mut self, kind: &'static str) {
        *self.invalid_readings.entry(kind).or_default() += 1;
    }

    /// Invalid readings of `kind` so far.
    pub fn invalid_readings(&self, kind: &str) -> u64 {
        self.invalid_readings.get(kind).copied().unwrap_or(0)
    }

    /// Every non-zero invalid-reading counter, by name.
    pub fn invalid_reading_counts(&self) -> impl Iterator<Item = (&'static str, u64)> + '_ {
        self.invalid_readings.iter().map(|(k, v)| (*k, *v))
    }

    /// Counts one expected event of `kind` (see the field's doc).
    pub fn note(&mut self, kind: &'static str) {
        *self.notes.entry(kind).or_default() += 1;
    }

    /// Expected events of `kind` so far.
    pub fn notes(&self, kind: &str) -> u64 {
        self.notes.get(kind).copied().unwrap_or(0)
    }

    /// Every non-zero expected-event counter, by name.
    pub fn note_counts(&self) -> impl Iterator<Item = (&'static str, u64)> + '_ {
        self.notes.iter().map(|(k, v)| (*k, *v))
    }

    /// All errors of every kind.
    pub fn total_errors(&self) -> u64 {
        self.errors.values().sum()
    }
}

impl fmt::Display for DeviceStats {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} scans, {} bytes, {} commands, {} handshakes, {} reconnects",
            self.scans, self.bytes, self.commands, self.handshakes, self.reconnects
        )?;
        let all = self.error_counts().chain(self.invalid_reading_counts());
        for (kind, n) in all.chain(self.note_counts()) {
            write!(f, ", {kind} {n}")?;
        }
        Ok(())
    }
}
