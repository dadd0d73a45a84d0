//! Emulators of real CAN sensors: the Continental ARS408-21 radar and
//! Benewake's CAN rangefinders. An emulator is fed the frames the host puts
//! on the bus and asked what it sent by a given time; it measures a scene
//! (moving spheres for the radar, a mesh for the rangefinders) and encodes
//! every frame through the builtin DBCs of `shroud_drivers::dbc`, the
//! same descriptions the drivers decode with. Pure: the caller carries the
//! frames (an SLCAN pty, a candump log) and passes the time.

pub mod ars408;
pub mod benewake;
mod bus;
mod catalog;
mod emulator;
mod signals;

#[cfg(test)]
mod tests;

pub use catalog::{can_emulator, CanEmulatorOptions, CanWorld, RangefinderSpec, CAN_MODELS};
pub use emulator::CanDeviceEmulator;
