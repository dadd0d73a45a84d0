//! MCAP recordings: `shroud record` writes the namespace's messages into an
//! MCAP file (exactly as they travelled), `shroud replay` publishes them
//! again with their timing, `shroud mcap info` says what a file holds, even
//! a truncated one. With `--ros2`, `shroud record` also writes a ROS 2 file
//! (`ros2_out.rs`), and `shroud replay` replays rosbag2 recordings
//! (`ros2_in.rs`). The decisions (topic filters, layout, chunks, splits,
//! drops, replay timing) are `shroud_record`'s; this is the I/O.

mod disk;
mod info;
mod mcap_file;
mod reader;
mod record;
mod replay;
mod ros2_in;
mod ros2_out;
mod shared;
mod views;
mod writer;

pub use info::{InfoArgs, TRUNCATED_EXIT};
pub use record::RecordArgs;
pub use replay::ReplayArgs;

use anyhow::Result;
use clap::Subcommand;

#[derive(Debug, Subcommand)]
pub enum McapCommand {
    /// Channels, schemas, counts, duration, size and compression of an MCAP
    /// file; a truncated file is reported with what it still holds (exit 3).
    Info(InfoArgs),
}

pub fn run_mcap(command: &McapCommand) -> Result<()> {
    match command {
        McapCommand::Info(args) => info::run(args),
    }
}

pub fn record(args: RecordArgs) -> Result<()> {
    record::run(args)
}

pub fn replay(args: ReplayArgs) -> Result<()> {
    replay::run(args)
}
