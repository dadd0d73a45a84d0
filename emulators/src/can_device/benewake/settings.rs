//! A unit's CAN settings, in the three copies a Benewake unit keeps: the ones
//! it runs with, the ones commands have set since, and the saved ones.

use shroud_drivers::can::{MAX_EXTENDED_ID, MAX_STANDARD_ID};

/// Ids, frame type and bit rate of one unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CanSettings {
    /// The id it sends readings (and replies) on.
    pub tx_id: u32,
    /// The id it takes commands on (either frame format).
    pub rx_id: u32,
    /// It sends extended (29-bit) frames.
    pub extended: bool,
    /// TF03: bit/s (command 0x52). TFmini-i / TF02-i: the baud code of
    /// command 0x51 (0x08 = 250 kbit/s). Stored and saved; the emulated bus
    /// keeps the model's rate.
    pub bitrate: u32,
}

impl CanSettings {
    /// Whether the unit can send with these: the TX id fits its format.
    pub fn usable(&self) -> bool {
        let max = if self.extended {
            MAX_EXTENDED_ID
        } else {
            MAX_STANDARD_ID
        };
        self.tx_id <= max && self.rx_id <= MAX_EXTENDED_ID
    }
}
