//! The `shroud` binary: parses the command line, sets up logging, runs, and turns
//! any error into a message and a non-zero exit.

use clap::Parser;
use shroud_nodes::cli::{run, Cli, ExitWith};
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = Cli::parse();
    // `--log` wins over RUST_LOG; a filter that does not parse is an error,
    // not a silent fallback.
    let (source, text) = match (&cli.log, std::env::var("RUST_LOG")) {
        (Some(log), _) => ("--log", log.clone()),
        (None, Ok(env)) if !env.is_empty() => ("RUST_LOG", env),
        _ => ("default", "warn".to_string()),
    };
    let filter = match tracing_subscriber::EnvFilter::try_new(&text) {
        Ok(filter) => filter,
        Err(e) => {
            eprintln!("error: invalid log filter {text:?} from {source}: {e}");
            return ExitCode::from(2);
        }
    };
    // Colour only on a terminal: a launcher reading a child's pipe wants plain text.
    // A log line that cannot be written (a closed pipe) is dropped, not
    // reported with `eprintln!`, which would panic on the same broken stderr.
    tracing_subscriber::fmt()
        .with_env_filter(filter)
        .log_internal_errors(false)
        .with_ansi(std::io::IsTerminal::is_terminal(&std::io::stderr()))
        .with_writer(std::io::stderr)
        .init();
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error:#}");
            match error.downcast_ref::<ExitWith>() {
                Some(exit) => ExitCode::from(exit.code),
                None => ExitCode::FAILURE,
            }
        }
    }
}
