//! Introspection of a running graph: `shroud topic list | echo | hz`. (`shroud
//! node list` lives with the nodes.)

mod echo;
mod hz;
mod list;
mod tool;

use anyhow::Result;
use clap::Subcommand;

pub use tool::{resolve_topic, ToolArgs};

#[derive(Debug, Subcommand)]
pub enum TopicCommand {
    /// Topics seen in the namespace during a short listen, with counts and sizes.
    List(list::TopicListArgs),
    /// Print messages of a topic as JSON lines (bulk blobs summarised).
    Echo(echo::EchoArgs),
    /// Message rate and bandwidth of a topic, once a second.
    Hz(hz::HzArgs),
}

pub fn run(command: TopicCommand) -> Result<()> {
    match command {
        TopicCommand::List(args) => list::run(args),
        TopicCommand::Echo(args) => echo::run(args),
        TopicCommand::Hz(args) => hz::run(args),
    }
}
