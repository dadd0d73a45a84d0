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
mod guard_separation;
mod guard_soundness;
mod latency;
mod paper000;
mod peers;
mod ros2_cdr;
mod soak;

use anyhow::Result;
use clap::parser::ValueSource;
use clap::{CommandFactory, FromArgMatches, Parser, ValueEnum};
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
    /// The guard's speed and separation monitoring in closed loop:
    /// `--trajectories` simulated arms running random trajectories at the
    /// scale of their verdicts among solids and people moving at up to
    /// `--obstacle-speed` (1.6 m/s here); counts the moments the moving arm
    /// came within the stop distance (must be 0) and compares productivity
    /// with a binary stop.
    GuardSeparation,
    /// shroud's 20 x 20 surrogate with the guard's 50-sphere check against
    /// an elevation map (per-cell maxima) and OctoMap + FCL (Python
    /// bindings, in a venv made under the target directory) on the same
    /// scanned clouds: build time, memory, query time, and test spheres
    /// called free that truly touch (unsafe) or blocked that are clear.
    Peers,
    /// shroud-ros2's CDR codec against the `cdr` and `cdr-encoding` crates
    /// on one PointCloud2 of `--points` points, beside one copy of the payload.
    Ros2Cdr,
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
    /// Guard soundness and separation: bound on the solids' speed, also the
    /// guard's max_obstacle_speed (m/s; guard-separation: 1.6 unless given).
    #[arg(long, default_value_t = 0.25)]
    pub obstacle_speed: f64,
    /// Whether --obstacle-speed was given (guard-separation's default differs).
    #[arg(skip)]
    pub obstacle_speed_given: bool,
    /// Guard soundness and separation: share of views fitted as sandwiches
    /// (else upper; guard-separation: 0 unless given).
    #[arg(long, default_value_t = 0.5)]
    pub sandwich_share: f64,
    /// Whether --sandwich-share was given (guard-separation's default differs).
    #[arg(skip)]
    pub sandwich_share_given: bool,
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
    /// Guard soundness: besides its whole view, fit each cloud that states
    /// its field of view in N x N overlapping sectors, each along its own
    /// axis, as fit nodes with `sectors` do (0: the whole view only).
    #[arg(long, default_value_t = 4)]
    pub sectors: usize,
    /// Guard soundness: how far a sector reaches, in its grid cell's angular
    /// half-diagonals (>= 1; never past the field of view).
    #[arg(long, default_value_t = 1.5)]
    pub sector_reach: f64,
    /// Guard separation: closed-loop trajectories to simulate (each seeded
    /// from --seed and its index; a failure prints its seed for --replay).
    #[arg(long, default_value_t = 10_000)]
    pub trajectories: u64,
    /// Guard separation: simulated seconds per trajectory.
    #[arg(long, default_value_t = 3.0)]
    pub duration: f64,
    /// Guard separation: most rays per scan (default: the library's).
    #[arg(long)]
    pub max_rays: Option<usize>,
    /// Guard separation: perspective sensors stating their field of view
    /// and empty rays, instead of parallel rays.
    #[arg(long)]
    pub perspective: bool,
    /// Guard separation: skip the binary guard's run (no productivity comparison).
    #[arg(long)]
    pub no_binary: bool,
    /// Guard separation: how the simulated arm treats its verdicts (the
    /// other values are negative controls that must fail).
    #[arg(long, value_enum, default_value = "obeys")]
    pub arm: guard_separation::ArmChoice,
    /// Guard separation: the negative control's amount (seconds late, or
    /// the factor of soft brakes).
    #[arg(long, default_value_t = 0.2)]
    pub arm_amount: f64,
    /// Guard separation, negative control: the obstacle speed the guard is
    /// told (the solids keep --obstacle-speed).
    #[arg(long)]
    pub declared_obstacle_speed: Option<f64>,
    /// Guard separation: how much higher than in the soundness scenes the
    /// arms are mounted (m).
    #[arg(long, default_value_t = 0.8)]
    pub mount_lift: f64,
    /// Guard separation: every shape of every waypoint is at least this
    /// high above the floor (m).
    #[arg(long, default_value_t = 1.0)]
    pub min_height: f64,
    /// Guard separation: share of trajectories with a person walking across.
    #[arg(long, default_value_t = 0.5)]
    pub person_share: f64,
    /// Guard separation: share of joint states carrying measured velocities.
    #[arg(long, default_value_t = 0.75)]
    pub velocities_share: f64,
    /// Guard separation: run the one trajectory with this seed (decimal or
    /// 0x hex, as a failure prints it), printing its scene.
    #[arg(long)]
    pub replay: Option<String>,
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
        Suite::GuardSeparation => guard_separation::run_bench(&args),
        Suite::Ros2Cdr => ros2_cdr::run(&args),
        Suite::Peers => peers::run(&args),
    }
}

/// An error is printed with its causes on one line, and exits 1.
fn main() -> ExitCode {
    let matches = BenchArgs::command().get_matches();
    let mut args = BenchArgs::from_arg_matches(&matches).unwrap_or_else(|e| e.exit());
    let given = |id: &str| matches.value_source(id) == Some(ValueSource::CommandLine);
    args.obstacle_speed_given = given("obstacle_speed");
    args.sandwich_share_given = given("sandwich_share");
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
