//! Tests of the CAN device emulators: golden frames computed by hand from
//! the manuals' byte layouts (so a DBC mistake cannot hide on both sides),
//! cycle structure and timing, configuration commands, and the scene.
//! Frames are otherwise decoded with the builtin DBCs, as a driver would.

mod ars408;
mod benewake;
mod catalog;

use crate::can_device::CanDeviceEmulator;
use shroud_drivers::can::CanFrame;

/// Everything `device` sends up to `until`, polled every 50 ms as a node
/// would (polls at times already past return nothing new).
pub(super) fn run(device: &mut dyn CanDeviceEmulator, until: f64) -> Vec<(f64, CanFrame)> {
    let mut out = Vec::new();
    let mut t = 0.0;
    while t < until {
        device.poll(t, &mut out);
        t += 0.05;
    }
    device.poll(until, &mut out);
    out
}

/// As [`run`], to just past `until`: a frame ready at `until` is on the
/// wire until its last bit, so it arrives a fraction of a millisecond later.
pub(super) fn run_past(device: &mut dyn CanDeviceEmulator, until: f64) -> Vec<(f64, CanFrame)> {
    run(device, until + 0.002)
}

/// A frame from hex, e.g. `frame(0x200, "F8000000089C0000")`.
pub(super) fn frame(id: u32, extended: bool, hex: &str) -> CanFrame {
    let bytes: Vec<u8> = (0..hex.len())
        .step_by(2)
        .map(|i| u8::from_str_radix(&hex[i..i + 2], 16).unwrap())
        .collect();
    CanFrame::new(id, extended, &bytes).unwrap()
}
