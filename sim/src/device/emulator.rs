//! What every device emulator implements, and what it measures.

/// One return of a ray.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RayReturn {
    /// Metres along the ray.
    pub range: f64,
    /// How well the surface reflects, in [0, 1] (devices turn it into their
    /// own intensity or strength scale).
    pub reflectance: f64,
}

/// The world as a device sees it: the first surface along a ray of its scan
/// plane. Implementations place the sensor (a mount that may tilt or rotate
/// over time) and cast into a scene.
pub trait RaySource: Send {
    /// The return of the ray leaving the sensor at `angle` radians
    /// (counter-clockwise from the sensor's +x, in its scan plane, REP-103) at
    /// `time` seconds of emulator time, if a surface lies within `max_range`
    /// metres. No noise: the emulator adds its device's own.
    fn cast(&self, angle: f64, time: f64, max_range: f64) -> Option<RayReturn>;
}

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
