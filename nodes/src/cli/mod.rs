//! The `shroud` command line: one subcommand per job.

mod blend;
mod blend_cmd;
mod certs;
mod demo;
pub mod fit;
mod query;
pub mod sensor_sim;
mod sim;
mod smooth;

pub use crate::exit::ExitWith;
pub use fit::certificate_line;

use anyhow::Result;
use clap::{Parser, Subcommand};

#[derive(Debug, Parser)]
#[command(
    name = "shroud",
    version,
    about = "Safe spline surrogates for live point clouds"
)]
pub struct Cli {
    /// Log filter (tracing env-filter syntax), e.g. `info` or `shroud=debug`.
    /// Default: the `RUST_LOG` environment variable, else `warn`.
    #[arg(long, global = true)]
    pub log: Option<String>,
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Stream the simulator's moving spheres through a warm-started fitter, live.
    Demo(demo::DemoArgs),
    /// Fit a certified safe spline surrogate to a point cloud file.
    Fit(fit::FitArgs),
    /// Generate a test scene (the paper's moving spheres, terrain, table top).
    Sim(sim::SimArgs),
    /// Query a surrogate: classify a point, cast a ray, bound a region.
    Query(query::QueryArgs),
    /// Run one node of the graph in this process (scanner, fit, guard, arm, ...),
    /// or list the running nodes.
    #[command(subcommand)]
    Node(crate::node::NodeCommand),
    /// Inspect the topics of a running graph: list, echo, hz.
    #[command(subcommand)]
    Topic(crate::introspect::TopicCommand),
    /// Start a graph of nodes from a launch file and supervise it.
    Launch(crate::launch::LaunchArgs),
    /// Simulate a serial or CAN range sensor: a pty or serial port (serial/slcan), or a candump log.
    SensorSim(sensor_sim::SensorSimArgs),
    /// Drop a child point cloud onto a parent and blend them (paper 001).
    Blend(blend::BlendArgs),
    /// Send drop/adjust/clear/commit commands (or a whole drag) to a `blend` node.
    BlendCmd(blend_cmd::BlendCmdArgs),
    /// Record the namespace's messages into an MCAP file (until Ctrl-C or --duration).
    Record(crate::recording::RecordArgs),
    /// Publish the shroud messages of an MCAP recording with their original timing.
    Replay(crate::recording::ReplayArgs),
    /// MCAP files: `shroud mcap info FILE`.
    #[command(subcommand)]
    Mcap(crate::recording::McapCommand),
    /// The G1 smooth fitter's domain (paper 004): mesh classification and the
    /// dimension of its G1 space (`--info`).
    Smooth(smooth::SmoothArgs),
    /// A development certificate authority and a certificate per host, for
    /// mutual TLS between a graph's hosts.
    Certs(certs::CertsArgs),
    /// A zenoh router: where hosts meet, with mutual TLS and the access
    /// control of a graph file's hosts; its status is on the bus.
    Router(crate::router::RouterArgs),
}

pub fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Demo(args) => demo::run(args),
        Command::Fit(args) => fit::run(args),
        Command::Sim(args) => sim::run(args),
        Command::Query(args) => query::run(args),
        Command::Node(command) => crate::node::run(command),
        Command::Topic(command) => crate::introspect::run(command),
        Command::Launch(args) => crate::launch::run(args),
        Command::SensorSim(args) => sensor_sim::run_sensor_sim(&args),
        Command::Blend(args) => blend::run(&args),
        Command::BlendCmd(args) => blend_cmd::run(args),
        Command::Smooth(args) => smooth::run(&args),
        Command::Record(args) => crate::recording::record(args),
        Command::Replay(args) => crate::recording::replay(args),
        Command::Mcap(command) => crate::recording::run_mcap(&command),
        Command::Certs(args) => certs::run(&args),
        Command::Router(args) => crate::router::run(args),
    }
}
