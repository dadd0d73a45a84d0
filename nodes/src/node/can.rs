//! The `can` node: a real range sensor on a CAN bus (SocketCAN, an SLCAN
//! adapter or a candump log). A blocking reader (from `crate::ingest`) decodes
//! scans; each is published as a cloud.

use super::runtime::{run_node, NodeCommon};
use super::scan_publisher::{cloud_publisher, max_skew_ns};
use crate::ingest::{run_can_reader, CanReaderConfig, CanSourceSpec};
use anyhow::Result;
use clap::Args;

#[derive(Debug, Clone, Args)]
pub struct CanNodeArgs {
    #[command(flatten)]
    pub common: NodeCommon,
    /// `socketcan:IFACE`, `slcan:PATH[@BAUD][:BITRATE]` or `candump:PATH[@SPEED|@max]`.
    #[arg(long)]
    pub source: String,
    /// Stream name: clouds go to `shroud/<ns>/cloud/<stream>`.
    #[arg(long, default_value = "can")]
    pub stream: String,
    /// A device (or log) stamp further than this (seconds) from this node's
    /// clock is counted as `clock_skew` (`inf`: no check, for old logs).
    #[arg(long, default_value_t = 5.0)]
    pub max_skew: f64,
}

pub fn run_can(args: CanNodeArgs) -> Result<()> {
    let max_skew_ns = max_skew_ns(args.max_skew)?;
    let spec: CanSourceSpec = args
        .source
        .parse()
        .map_err(|e| anyhow::anyhow!("--source {:?}: {e}", args.source))?;
    let common = args.common.clone();
    run_node(&common, "can", move |ctx| {
        let mut publish = cloud_publisher(&ctx, &args.stream, &args.source, max_skew_ns)?;
        let stats = run_can_reader(
            &mut || spec.open(),
            &CanReaderConfig::default(),
            &mut publish,
            ctx.stop_flag(),
        )?;
        tracing::info!("CAN reader stopped: {stats}");
        Ok(())
    })
}
