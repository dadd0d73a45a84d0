//! `shroud-bench`, the benchmark harness (its own binary, not shipped with
//! `shroud`): reproduces the timing tables of paper 000 on the paper's own
//! scene beside the paper's numbers, and measures the graph, the drivers and
//! the guard (markdown, for docs/benchmarks.md). The graph suites (latency,
//! consumers, soak) run their nodes with the `shroud` binary built next to it.

mod can;
mod consumers;
mod devices;
mod encode;
mod foxglove_clients;
mod graph;
mod guard_soundness;
mod latency;
mod paper000;
mod soak;

use anyhow::Result;
use clap::{Parser, ValueEnum};
use shroud_nodes::timing::{median, timed};
use std::process::ExitCode;

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Suite {
    /// Tables 1 and 2, the Figure 9 histograms and the Section 3 baseline.
    Surrogate,
    /// End-to-end latency through a real fit node process over zenoh.
    Latency,
    /// Decode throughput of the real-device drivers (Hokuyo, RPLIDAR,
    /// Benewake) on recorded emulator streams, and last byte to encoded cloud.
    Devices,
    /// The CAN device layer: generic DBC decode against a hand-shifted
    /// decoder, and the ARS408 and Benewake CAN drivers on recorded emulator
    /// traffic, with last frame to encoded cloud.
    Can,
    /// What watching the graph costs it: the fit latency with no consumer and
    /// with the dashboard and 0, 1, 3 headless browsers (`--browsers`), with
    /// each consumer's CPU share.
    Consumers,
    /// The demo graph for `--minutes`: memory, CPU, latency, drops and
    /// shared memory per window, memory slopes, cloud accounting (`--check`).
    Soak,
    /// The collision guard against exact geometry: `--cases` random scenes
    /// of moving solids scanned by random sensors, `--verdicts-per-case`
    /// verdicts each; counts optimistic `clear` verdicts (must be 0).
    GuardSoundness,
}

#[derive(Debug, Parser)]
#[command(
    version,
    about = "Reproduce the paper's timing tables and measure ours"
)]
pub struct BenchArgs {
    #[arg(value_enum, default_value = "surrogate")]
    pub suite: Suite,
    /// Cloud configurations per table entry (the paper used 10).
    #[arg(long, default_value_t = 10)]
    pub configs: usize,
    /// Fits per configuration (the paper used 20).
    #[arg(long, default_value_t = 20)]
    pub runs: usize,
    /// A fast smoke run: 2 configurations x 3 fits, small clouds only.
    #[arg(long)]
    pub quick: bool,
    /// Seconds per row of the latency and consumers tables.
    #[arg(long, default_value_t = 10.0)]
    pub seconds: f64,
    /// Points per cloud of the scanner (consumers).
    #[arg(long, default_value_t = 300_000)]
    pub points: usize,
    /// Clouds per second of the scanner (consumers).
    #[arg(long, default_value_t = 30.0)]
    pub rate: f64,
    /// Browser counts to measure the dashboard with, comma-separated (consumers).
    #[arg(long, default_value = "0,1,3")]
    pub browsers: String,
    /// Minutes the soak runs.
    #[arg(long, default_value_t = 10.0)]
    pub minutes: f64,
    /// Seconds per line of the soak's table.
    #[arg(long, default_value_t = 60.0)]
    pub window: f64,
    /// Soak: fail when a cloud is unaccounted for or a node's memory grew
    /// by more than --max-growth-mb between the first and the last window.
    #[arg(long)]
    pub check: bool,
    /// Soak: the memory growth --check allows per node, MB.
    #[arg(long, default_value_t = 16.0)]
    pub max_growth_mb: f64,
    /// Guard soundness: random scenes to draw.
    #[arg(long, default_value_t = 10_000)]
    pub cases: u64,
    /// Guard soundness: seed of the first scene (each scene's seed is
    /// printed with any finding, to replay it alone).
    #[arg(long, default_value_t = 23)]
    pub seed: u64,
    /// Guard soundness: verdicts per scene (arm poses x decision times).
    #[arg(long, default_value_t = 100)]
    pub verdicts_per_case: usize,
    /// Guard soundness: bound on the solids' speed, also the guard's
    /// max_obstacle_speed (m/s).
    #[arg(long, default_value_t = 0.25)]
    pub obstacle_speed: f64,
    /// Guard soundness: share of views fitted as sandwiches (else upper).
    #[arg(long, default_value_t = 0.5)]
    pub sandwich_share: f64,
    /// Guard soundness: share of black solids (no range returned).
    #[arg(long, default_value_t = 0.15)]
    pub black_share: f64,
    /// Guard soundness: sensors cast parallel rays along their look (the
    /// sensor the guard's views assume) instead of rays from a point.
    #[arg(long)]
    pub parallel_rays: bool,
    /// Guard soundness: clouds do not state their sensor's field of view
    /// (the guard then trusts kept triangles at the edge of a view).
    #[arg(long)]
    pub no_field_of_view: bool,
    /// Guard soundness: clouds do not list the directions in which their
    /// rays returned nothing (the guard then trusts kept triangles
    /// interpolated across a black solid).
    #[arg(long)]
    pub no_empty_rays: bool,
}

fn run(args: BenchArgs) -> Result<()> {
    match args.suite {
        Suite::Surrogate => paper000::run(&args),
        Suite::Latency => latency::run(&args),
        Suite::Devices => devices::run(&args),
        Suite::Can => can::run(&args),
        Suite::Consumers => consumers::run(&args),
        Suite::Soak => soak::run(&args),
        Suite::GuardSoundness => guard_soundness::run_bench(&args),
    }
}

/// An error is printed with its causes on one line, and exits 1.
fn main() -> ExitCode {
    let args = BenchArgs::parse();
    // Warnings of the libraries (zenoh's included) on standard error, unless
    // RUST_LOG asks for more; the tables go to standard output.
    let filter = tracing_subscriber::EnvFilter::try_from_default_env()
        .unwrap_or_else(|_| tracing_subscriber::EnvFilter::new("warn"));
    tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_writer(std::io::stderr)
        .init();
    let failed = |error: anyhow::Error| {
        eprintln!("error: {error:#}");
        ExitCode::FAILURE
    };
    run(args).map_or_else(failed, |()| ExitCode::SUCCESS)
}
