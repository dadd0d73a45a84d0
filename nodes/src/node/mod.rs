//! The node programs, each run as its own process with `shroud node <kind>`,
//! and `shroud node list`.

mod arm;
mod blend;
mod can;
mod dashboard;
mod device;
mod device_sim;
mod device_status;
mod fit;
mod foxglove_bridge;
mod guard;
mod list;
mod ros2;
mod scan_publisher;
mod scanner;
mod serial;
mod smooth;
mod viewer;

pub use crate::runtime::{run_node, NodeCommon, NodeContext, NodeMetrics};
pub use arm::ArmArgs;
pub use blend::BlendNodeArgs;
pub use can::CanNodeArgs;
pub use dashboard::DashboardArgs;
pub use device_sim::DeviceSimArgs;
pub use fit::FitNodeArgs;
pub use foxglove_bridge::FoxgloveArgs;
pub use guard::GuardArgs;
pub use list::NodeListArgs;
pub use ros2::Ros2Args;
pub use scanner::ScannerArgs;
pub use serial::SerialNodeArgs;
pub use smooth::SmoothNodeArgs;

use anyhow::Result;
use clap::Subcommand;

#[derive(Debug, Subcommand)]
pub enum NodeCommand {
    /// Publish simulated clouds (moving spheres, terrain, table top, mesh scans).
    Scanner(ScannerArgs),
    /// Fit certified surrogates to a cloud stream.
    Fit(FitNodeArgs),
    /// Collision guard: per-link clearance of an arm against the surrogate sandwich.
    Guard(GuardArgs),
    /// A simulated arm following a trajectory, halting when the guard says stop.
    Arm(ArmArgs),
    /// A serial range sensor (docs/sensor-protocols.md section 1) published as clouds.
    Serial(SerialNodeArgs),
    /// An emulated real range sensor (Hokuyo, RPLIDAR, Benewake) on a pseudo-terminal.
    DeviceSim(DeviceSimArgs),
    /// A CAN range sensor (SocketCAN, SLCAN or a candump log) published as clouds.
    Can(CanNodeArgs),
    /// Blend a child part onto a parent cloud, following drop/adjust commands (paper 001).
    Blend(BlendNodeArgs),
    /// Fit G1 smooth spline patches to a cloud stream over a domain (paper 004).
    Smooth(SmoothNodeArgs),
    /// The live monitoring page: serves it over HTTP and streams the graph to browsers.
    Dashboard(DashboardArgs),
    /// The Foxglove WebSocket bridge: the graph in Foxglove or Lichtblick, drops from their Publish panel.
    Foxglove(FoxgloveArgs),
    /// Join a ROS 2 system over rmw_zenoh: PointCloud2 and JointState in; verdicts, markers and clouds out.
    Ros2(Ros2Args),
    /// Record the namespace's messages into an MCAP file (as `shroud record`).
    Record(crate::recording::RecordArgs),
    /// Publish an MCAP recording's shroud messages, in place of a sensor (as `shroud replay`).
    Replay(crate::recording::ReplayArgs),
    /// List the nodes alive in a namespace with their status.
    List(NodeListArgs),
}

pub fn run(command: NodeCommand) -> Result<()> {
    match command {
        NodeCommand::Scanner(args) => scanner::run(args),
        NodeCommand::Fit(args) => fit::run(args),
        NodeCommand::Guard(args) => guard::run(args),
        NodeCommand::Arm(args) => arm::run(args),
        NodeCommand::Serial(args) => serial::run_serial(args),
        NodeCommand::Can(args) => can::run_can(args),
        NodeCommand::DeviceSim(args) => device_sim::run_device_sim(args),
        NodeCommand::Blend(args) => blend::run(args),
        NodeCommand::Smooth(args) => smooth::run(args),
        NodeCommand::Dashboard(args) => dashboard::run(args),
        NodeCommand::Foxglove(args) => foxglove_bridge::run(args),
        NodeCommand::Ros2(args) => ros2::run(args),
        NodeCommand::Record(args) => crate::recording::record(args),
        NodeCommand::Replay(args) => crate::recording::replay(args),
        NodeCommand::List(args) => list::run(args),
    }
}
