//! Emulated Benewake rangefinders with a CAN interface (TF03-CAN,
//! TFmini-i-CAN, TF02-i-CAN, legacy TF02 CAN; sensors.md §2.1): readings at
//! 100 Hz through the builtin Benewake DBCs, several units sharing one bus,
//! and the `5A` CAN configuration commands.

mod command;
mod emulator;
mod measure;
mod model;
mod settings;

pub use emulator::{BenewakeCanCounts, BenewakeCanEmulator, UnitSpec, MAX_UNITS};
pub use measure::range_noise_m;
pub use model::BenewakeCanModel;
pub use settings::CanSettings;
