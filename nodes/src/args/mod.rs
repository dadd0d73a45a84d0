//! Command-line option groups that a CLI subcommand and a node share, or that
//! several nodes share, in one place so that neither imports the other.

mod blend;
mod can_device;
mod device;
mod emulator;
mod mount;
mod ros_cloud;
mod smooth;
mod surrogate;
mod viewer;
mod web_listen;

pub use blend::{points3, BlendShapeArgs};
pub use can_device::{
    parse_can_id, read_dbc, CanDeviceArgs, CanDeviceKind, RadarOutputArg, RangefinderArg,
};
pub use device::{DeviceArgs, DeviceKind, RplidarScan, ScipScan};
pub use emulator::EmulatorArgs;
pub use mount::{CloudArgs, MountArgs, MountAxis};
pub use ros_cloud::RosCloudArgs;
pub use smooth::{DomainKind, SmoothDomainArgs};
pub use surrogate::SurrogateShapeArgs;
pub use viewer::{ViewLimits, ViewerArgs, ViewerSettings};
pub use web_listen::take_web_listen;
