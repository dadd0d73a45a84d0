//! The `serial` node: a range sensor on a serial port published as clouds on
//! `cloud/<stream>`. shroud's own protocol goes through the protocol reader
//! (its scans are already 3D); a real device (Hokuyo, ...) through its driver
//! and the scan-to-cloud assembly of its mount.

use super::device::run_device_clouds;
use super::scan_publisher::{cloud_publisher, max_skew_ns};
use crate::args::{CloudArgs, DeviceArgs};
use crate::ingest::{run_serial_reader, DevicePortConfig, SerialReaderConfig};
use crate::runtime::{run_node, NodeCommon};
use anyhow::{bail, Result};
use clap::Args;
use shroud_drivers::assembly::{MountPose, MovingMount};

#[derive(Debug, Clone, Args)]
pub struct SerialNodeArgs {
    #[command(flatten)]
    pub common: NodeCommon,
    /// Serial device (`/dev/ttyUSB0`, `/dev/serial/by-id/...`, a pty).
    #[arg(long)]
    pub port: String,
    #[command(flatten)]
    pub device: DeviceArgs,
    #[command(flatten)]
    pub clouds: CloudArgs,
    /// Stream name: clouds go to `shroud/<ns>/cloud/<stream>`.
    #[arg(long, default_value = "serial")]
    pub stream: String,
    /// A device stamp further than this (seconds) from this node's clock is
    /// counted as `clock_skew` (stamps are kept, never used for decisions).
    #[arg(long, default_value_t = 5.0)]
    pub max_skew: f64,
}

pub fn run_serial(args: SerialNodeArgs) -> Result<()> {
    let max_skew_ns = max_skew_ns(args.max_skew)?;
    let baud = args.device.port_baud();
    // Every setting is checked before the node starts.
    let driver = args.device.driver()?;
    let assembly = args.clouds.assembly()?;
    shroud_drivers::assembly::CloudAssembler::new(assembly.clone())?;
    let common = args.common.clone();
    match driver {
        None => {
            let unmoved = MovingMount::fixed(MountPose::default());
            if assembly.mount != unmoved || args.clouds.cloud.is_some() {
                bail!(
                    "--device shroud sends 3D scans in its own frame: --mount, --sensor-offset, \
                     --sweep, --mount-joint and --cloud apply to range devices only"
                );
            }
            let config = SerialReaderConfig::new(&args.port, baud);
            run_node(&common, "serial", move |ctx| {
                let mut publish = cloud_publisher(&ctx, &args.stream, &args.port, max_skew_ns)?;
                let stats = run_serial_reader(&config, &mut publish, ctx.stop_flag())?;
                tracing::info!("serial reader stopped: {stats}");
                Ok(())
            })
        }
        Some(mut driver) => {
            let port = DevicePortConfig {
                read_timeout: args.device.port_read_timeout(),
                ..DevicePortConfig::new(&args.port, baud)
            };
            run_node(&common, "serial", move |ctx| {
                run_device_clouds(
                    &ctx,
                    driver.as_mut(),
                    &port,
                    &args.clouds,
                    &args.stream,
                    max_skew_ns,
                )
            })
        }
    }
}
