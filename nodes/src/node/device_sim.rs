//! The `device-sim` node: an emulated real range sensor on a pseudo-terminal
//! (as `shroud sensor-sim --device`; a CAN device behind an emulated SLCAN
//! adapter), supervised by a launch file, with its line's counters in the
//! node's status.

use crate::args::EmulatorArgs;
use crate::ingest::run_emulator;
use crate::runtime::{run_node, NodeCommon};
use anyhow::{Context, Result};
use clap::Args;
use shroud_graph::metrics::names as metric;

#[derive(Debug, Clone, Args)]
pub struct DeviceSimArgs {
    #[command(flatten)]
    pub common: NodeCommon,
    /// The device model: urg-04lx, utm-30lx, rplidar-a1, rplidar-a2, tfmini,
    /// tfmini-s, tfmini-plus, tf-luna, tf02-pro; or a CAN device behind an
    /// emulated SLCAN adapter: ars408, tf03-can, tfmini-i-can, tf02-i-can,
    /// tf02-can.
    #[arg(long)]
    pub device: String,
    #[command(flatten)]
    pub emulator: EmulatorArgs,
    /// Corrupt the checksum of every n-th scan; 0 = never.
    #[arg(long, default_value_t = 0)]
    pub corrupt_every: u64,
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
}

pub fn run_device_sim(args: DeviceSimArgs) -> Result<()> {
    // Settings and the world are checked before the node starts.
    let mut make = args
        .emulator
        .maker(&args.device, args.corrupt_every, args.seed)?;
    let line = args.emulator.line();
    let common = args.common.clone();
    run_node(&common, "device-sim", move |ctx| {
        ctx.metrics
            .set_label("device.model".into(), args.device.clone());
        let mut ready = |path: &std::path::Path| {
            tracing::info!("emulated {} on {}", args.device, path.display());
            ctx.metrics
                .set_label("device.path".into(), path.display().to_string());
        };
        let mut on_stats = |s: &crate::ingest::LineStats| {
            let m = &ctx.metrics;
            m.set_counter(metric::BYTES_TO_HOST, s.bytes_to_host);
            m.set_counter(metric::BYTES_FROM_HOST, s.bytes_from_host);
            m.set_counter(metric::BYTES_DROPPED, s.bytes_dropped);
            m.set_counter(metric::BYTES_GARBLED, s.bytes_garbled);
            m.set_counter(metric::UNPLUGS, s.unplugs);
        };
        let stats = run_emulator(&mut make, &line, ctx.stop_flag(), &mut ready, &mut on_stats)
            .context("emulated device")?;
        on_stats(&stats);
        Ok(())
    })
}
