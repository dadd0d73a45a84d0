//! The `serial` node: a real range sensor on a serial port. A blocking reader
//! (from `crate::ingest`) decodes scans; each is published as a cloud.

use super::runtime::{run_node, NodeCommon};
use super::scan_publisher::{cloud_publisher, max_skew_ns};
use crate::ingest::{run_serial_reader, SerialReaderConfig};
use anyhow::Result;
use clap::Args;

#[derive(Debug, Clone, Args)]
pub struct SerialNodeArgs {
    #[command(flatten)]
    pub common: NodeCommon,
    /// Serial device (`/dev/ttyUSB0`, `/dev/serial/by-id/...`, a pty).
    #[arg(long)]
    pub port: String,
    #[arg(long, default_value_t = 921_600)]
    pub baud: u32,
    /// Stream name: clouds go to `shroud/<ns>/cloud/<stream>`.
    #[arg(long, default_value = "serial")]
    pub stream: String,
    /// A device stamp further than this (seconds) from this node's clock is
    /// counted as `clock_skew` (stamps are kept, never used for decisions).
    #[arg(long, default_value_t = 5.0)]
    pub max_skew: f64,
}

pub fn run_serial(args: SerialNodeArgs) -> Result<()> {
    let config = SerialReaderConfig::new(&args.port, args.baud);
    let max_skew_ns = max_skew_ns(args.max_skew)?;
    let common = args.common.clone();
    run_node(&common, "serial", move |ctx| {
        let mut publish = cloud_publisher(&ctx, &args.stream, &args.port, max_skew_ns)?;
        let stats = run_serial_reader(&config, &mut publish, ctx.stop_flag())?;
        tracing::info!("serial reader stopped: {stats}");
        Ok(())
    })
}
