//! The `shroud` binary: parses the command line, sets up logging, runs, and turns
//! any error into a message and a non-zero exit.

use clap::Parser;
use shroud_nodes::cli::{run, Cli};
use std::process::ExitCode;

#[global_allocator]
static ALLOCATOR: shroud_nodes::bench::CountingAllocator = shroud_nodes::bench::CountingAllocator;

fn main() -> ExitCode {
    let cli = Cli::parse();
    let filter = tracing_subscriber::EnvFilter::try_new(&cli.log)
        .unwrap_or_else(|_| tracing_subscriber::EnvFilter::new("warn"));
    // Colour only on a terminal: a launcher reading a child's pipe wants plain text.
    tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_ansi(std::io::IsTerminal::is_terminal(&std::io::stderr()))
        .with_writer(std::io::stderr)
        .init();
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error:#}");
            ExitCode::FAILURE
        }
    }
}
