//! What every serial device emulator implements, and the faults it can be told to show.

/// Misbehaviour an emulator can be told to show, on top of its device's own
/// noise and dropouts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Faults {
    /// Corrupt the checksum of every n-th scan (or frame, for a single-beam
    /// sensor); 0 = never.
    pub corrupt_every: u64,
    /// Send a burst of random bytes before every n-th scan; 0 = never.
    pub garbage_every: u64,
    /// Seed of the garbage bytes.
    pub seed: u64,
}

/// A serial device: fed what the host writes, asked what it has sent by a
/// given time. `now` is emulator time in seconds (monotonic, from 0 at
/// creation, passed by the caller; never read from a clock).
pub trait SerialDeviceEmulator: Send {
    /// The device model's name (`urg-04lx`, `rplidar-a1`, ...).
    fn model(&self) -> &'static str;
    /// Bytes the host wrote, at `now`.
    fn receive(&mut self, bytes: &[u8], now: f64);
    /// Appends to `out` every byte the device sends from the previous poll up
    /// to `now` (replies, then streamed data at the device's pace).
    fn poll(&mut self, now: f64, out: &mut Vec<u8>);
    /// The baud rate the device's UART runs at now, or `None` for a USB
    /// (CDC-ACM) device, where the rate is irrelevant. When the host's rate
    /// differs, the transport garbles bytes both ways, as a real line would.
    fn uart_baud(&self) -> Option<u32>;
    /// The host drove its DTR line (`true` = asserted). Devices without a use
    /// for it ignore it.
    fn set_dtr(&mut self, _asserted: bool, _now: f64) {}
}
