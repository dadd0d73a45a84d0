//! Byte-exact emulators of the sensors shroud drives, written from their
//! manuals: [`device`] holds the serial ones (Hokuyo SCIP 2.0 lidars, Slamtec
//! RPLIDARs, Benewake TFmini rangefinders), [`can_device`] the CAN ones (the
//! Continental ARS408-21 radar, Benewake's CAN rangefinders), and
//! [`SlcanAdapter`] puts a CAN device behind a USB SLCAN adapter. They
//! measure the scenes of `shroud_sim` (rays cast into its meshes, its moving
//! spheres). Pure: the caller carries the bytes and frames and passes the time.

pub mod can_device;
pub mod device;
mod slcan_adapter;

pub use slcan_adapter::SlcanAdapter;
