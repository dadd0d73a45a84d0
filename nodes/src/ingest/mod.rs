//! Sensor ingest on devices: blocking readers that turn serial and CAN range
//! sensors into [`Scan`]s, and writers that simulate such sensors. The codecs
//! (pure) are in `shroud_drivers`; the protocols are specified in
//! `docs/sensor-protocols.md`.
//!
//! Readers run on their own thread until a stop flag is set:
//!
//! ```no_run
//! use shroud_nodes::ingest::{run_serial_reader, SerialReaderConfig};
//! use std::sync::atomic::AtomicBool;
//! let stop = AtomicBool::new(false);
//! let config = SerialReaderConfig::new("/dev/ttyUSB0", 921_600);
//! let stats = run_serial_reader(&config, &mut |scan, _stats| {
//!     println!("scan {} with {} points", scan.sequence, scan.points.len());
//! }, &stop)?;
//! # Ok::<(), shroud_nodes::ingest::ReaderError>(())
//! ```
//!
//! - [`run_serial_reader`]: the serial protocol on a serial port;
//! - [`run_can_reader`]: the CAN protocol from any [`CanSource`]: SocketCAN
//!   ([`SocketCanSource`]), an SLCAN adapter ([`SlcanSource`]), a candump log
//!   ([`CandumpReplay`]) or an in-memory bus ([`memory_bus`]); [`CanSourceSpec`]
//!   names one in text (`socketcan:can0`, `slcan:/dev/ttyACM0@115200:500000`,
//!   `candump:run.log@max`);
//! - [`run_can_device`]: a real CAN sensor's driver
//!   (`shroud_drivers::{ars408, benewake_can}`) on any [`CanSource`];
//! - [`run_device`]: a real sensor's driver (`shroud_drivers::{scip,
//!   rplidar, benewake}`) on a serial port ([`DevicePortConfig`]);
//! - [`sim`]: the simulated sensors' writers behind `shroud sensor-sim`, and
//!   [`run_emulator`]: an emulated real device on a pseudo-terminal.

mod backoff;
mod can_device_bus;
mod can_reader;
mod can_source;
mod candump_source;
mod device_port;
mod emulated_device;
mod error;
mod memory_bus;
pub mod pty;
mod report;
mod serial;
pub mod sim;
mod slcan_source;
mod socketcan_source;
mod stats;

pub use backoff::{sleep_unless_stopped, BackoffConfig};
pub use can_device_bus::{run_can_device, BusStats};
pub use can_reader::{run_can_reader, CanReaderConfig, CanSourceSpec};
pub use can_source::{received_now, CanSource};
pub use candump_source::{CandumpReplay, ReplayPace};
pub use device_port::{host_now, run_device, DevicePortConfig, PortStats};
pub use emulated_device::{run_emulator, EmulatorLine, LineStats};
pub use error::{ReaderError, SourceError};
pub use memory_bus::{memory_bus, memory_bus_duplex, MemoryBus, MemoryBusSender};
pub use serial::{run_serial_reader, SerialReaderConfig};
pub use shroud_drivers::Scan;
pub use slcan_source::SlcanSource;
pub use socketcan_source::{from_socketcan, to_socketcan, SocketCanSource};
pub use stats::ReaderStats;
