//! The `shroud` command line: one subcommand per job.

mod demo;
mod fit;
mod query;
mod sim;

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
    #[arg(long, global = true, default_value = "warn")]
    pub log: String,
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
    /// Reproduce the paper's timing tables and measure ours.
    Bench(crate::bench::BenchArgs),
}

pub fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Demo(args) => demo::run(args),
        Command::Fit(args) => fit::run(args),
        Command::Sim(args) => sim::run(args),
        Command::Query(args) => query::run(args),
        Command::Bench(args) => crate::bench::run(args),
    }
}
