//! Counters of a device reader: the decoder's, plus the device's own life
//! (opens, failed opens, disconnects, bytes).

use shroud_drivers::DecoderStats;
use std::fmt;

/// What a reader did, summed over every (re)connection.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ReaderStats {
    /// The scan decoder's counters (serial protocol or CAN sensor protocol).
    pub decoder: DecoderStats,
    /// The transport's counters, for CAN sources that have one (SLCAN lines,
    /// candump lines); zero otherwise.
    pub transport: DecoderStats,
    /// Bytes read from a serial device (serial reader only).
    pub bytes_read: u64,
    /// CAN frames received from the source (CAN reader only).
    pub frames_received: u64,
    /// Successful opens of the device (1 + reconnections).
    pub opens: u64,
    /// Failed open attempts.
    pub open_failures: u64,
    /// Times the device went away after being opened.
    pub disconnects: u64,
    /// Scans handed to the callback.
    pub scans: u64,
}

impl fmt::Display for ReaderStats {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} scans; {} opens, {} failed opens, {} disconnects; decoder: {}",
            self.scans, self.opens, self.open_failures, self.disconnects, self.decoder
        )?;
        if self.transport.input > 0 {
            write!(f, "; transport: {}", self.transport)?;
        }
        Ok(())
    }
}
