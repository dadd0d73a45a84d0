//! Emulated Benewake UART rangefinders (TFmini, TFmini-S, TFmini Plus,
//! TF-Luna, TF02-Pro): 9-byte data frames at the frame rate with each
//! model's strength scale and invalid readings, and the `5A` command set
//! (version, reset, frame rate, trigger, output format, baud rate, output
//! enable, TF-Luna checksum switch, factory reset, save).
//!
//! Written from Benewake's product manuals (cited per file), independently
//! of the host driver.

mod command;
mod emulator;
mod faults;
mod frame;
mod measure;
mod model;
mod options;
mod rejects;
mod settings;

#[cfg(test)]
mod tests;

pub use emulator::BenewakeEmulator;
pub use model::BenewakeModel;
pub use options::BenewakeOptions;
pub use rejects::{RejectCounts, RejectKind};
