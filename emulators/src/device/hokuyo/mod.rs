//! Byte-exact emulators of the Hokuyo URG-04LX and UTM-30LX scanning lidars
//! speaking SCIP 2.0 (Hokuyo drawing C-42-03320B, "Communication Protocol
//! Specification for SCIP2.0"; page numbers below are that document's).
//!
//! [`HokuyoEmulator`] answers the SCIP 2.0 command set (VV, PP, II, BM, QT,
//! RS, RB, TM, SS, MD/MS, GD/GS and, on the UTM-30LX, ME/GE and the
//! multi-echo HD/ND/HE/NE) with the real replies, streams scans it measures
//! by casting rays into a [`RaySource`](crate::device::RaySource) at the
//! device's rotation rate, and paces its output at the RS-232 bit rate when
//! it sits on a serial line.
//! Pure: time is an argument, nothing here reads a clock or does I/O.

mod codec;
mod command;
mod device;
mod echo;
mod faults;
mod framer;
mod handlers;
mod info;
mod model;
mod options;
mod output;
mod scan;
mod stats;
mod status;
mod timing;

pub use device::HokuyoEmulator;
pub use model::HokuyoModel;
pub use options::{HokuyoOptions, Link};
pub use stats::{HokuyoStats, Rejection};

#[cfg(test)]
mod tests;
