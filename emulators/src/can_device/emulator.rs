//! What every CAN device emulator implements.

use shroud_drivers::can::CanFrame;

/// A CAN device: fed the frames the host sends, asked what it sent by a
/// given time. `now` is emulator time in seconds (monotonic from 0 at
/// creation, passed by the caller; never read from a clock).
pub trait CanDeviceEmulator: Send {
    /// The device model's name (one of [`CAN_MODELS`](super::CAN_MODELS)).
    fn model(&self) -> &'static str;
    /// A frame the host put on the bus at `now`. Frames for other devices
    /// (ids the device does not listen to) are ignored.
    fn receive(&mut self, frame: &CanFrame, now: f64);
    /// Appends every frame the device sends after the previous poll up to
    /// `now`, each with its send time in seconds (the moment its last bit
    /// left the bus, when a receiver has it), in order.
    fn poll(&mut self, now: f64, out: &mut Vec<(f64, CanFrame)>);
}
