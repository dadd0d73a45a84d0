//! Byte-exact emulators of real serial range sensors (Hokuyo SCIP 2.0 lidars,
//! Slamtec RPLIDARs, Benewake TFmini rangefinders, and an SLCAN adapter
//! with a CAN device on its bus). An emulator answers the
//! device's real command set with its real replies and streams scans it
//! measures by casting rays into a [`RaySource`]. Pure: the caller carries the
//! bytes (a pseudo-terminal in `shroud sensor-sim`) and passes the time.
//!
//! Written from the devices' manuals, independently of the drivers in
//! `shroud_drivers`: the golden vectors in both test suites are the
//! arbiter, so a misreading in one is not copied into the other.

pub mod benewake;
mod catalog;
mod emulator;
pub mod hokuyo;
pub mod rplidar;

pub use catalog::{emulator, EmulatorOptions, MODELS};
pub use emulator::{Faults, SerialDeviceEmulator};
pub use shroud_sim::world::{MeshRays, RayReturn, RaySource};
