//! The serial range-sensor reader: opens a port with `serialport`, feeds the
//! streaming decoder, hands complete scans to a callback, and survives the device
//! going away by reopening it with backoff until told to stop.

use super::backoff::{Backoff, BackoffConfig};
use super::report::ErrorReporter;
use super::{ReaderError, ReaderStats};
use shroud_drivers::serial::{DecoderConfig, SerialScanDecoder};
use shroud_drivers::Scan;
use std::io::{self, Read};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

/// Where and how to read a serial range sensor.
#[derive(Debug, Clone, PartialEq)]
pub struct SerialReaderConfig {
    /// Device path (`/dev/ttyUSB0`, `/dev/serial/by-id/...`, a pty slave).
    pub path: String,
    pub baud: u32,
    /// Longest a read blocks; also how quickly `stop` is noticed.
    pub read_timeout: Duration,
    pub backoff: BackoffConfig,
    pub decoder: DecoderConfig,
}

impl SerialReaderConfig {
    pub fn new(path: &str, baud: u32) -> Self {
        Self {
            path: path.to_owned(),
            baud,
            read_timeout: Duration::from_millis(100),
            backoff: BackoffConfig::default(),
            decoder: DecoderConfig::default(),
        }
    }
}

/// Reads scans from a serial range sensor (`docs/sensor-protocols.md` §1) until `stop` is set.
///
/// Blocking: run it on its own thread (or `spawn_blocking`). Every complete scan
/// goes to `on_scan` together with the counters so far. Decode errors are counted
/// and logged (`debug` each, a `warn` summary at most every 5 s); they never stop
/// the reader. When the device cannot be opened, or disappears (read error,
/// end of file, hang-up), the reader logs a `warn`, counts it, reports a partial
/// scan as incomplete, and reopens with backoff. It returns the final counters
/// once `stop` is set (within about `read_timeout`), or
/// [`ReaderError::Config`] at once for a zero baud rate or an empty path.
pub fn run_serial_reader(
    config: &SerialReaderConfig,
    on_scan: &mut dyn FnMut(Scan, &ReaderStats),
    stop: &AtomicBool,
) -> Result<ReaderStats, ReaderError> {
    if config.baud == 0 || config.path.is_empty() || config.read_timeout.is_zero() {
        return Err(ReaderError::Config(format!(
            "serial reader needs a path, a baud rate and a read timeout (got {:?}, {}, {:?})",
            config.path, config.baud, config.read_timeout
        )));
    }
    let mut stats = ReaderStats::default();
    let mut decoder = SerialScanDecoder::new(config.decoder);
    let mut reporter = ErrorReporter::new(&config.path);
    let mut backoff = Backoff::new(config.backoff);
    let mut buf = vec![0u8; 8192];
    while !stop.load(Ordering::Relaxed) {
        let opened = serialport::new(&config.path, config.baud)
            .timeout(config.read_timeout)
            .open();
        let mut port = match opened {
            Ok(port) => port,
            Err(error) => {
                stats.open_failures += 1;
                if stats.open_failures == 1 || stats.open_failures.is_power_of_two() {
                    tracing::warn!(path = %config.path, attempts = stats.open_failures,
                        "cannot open serial sensor: {error}; retrying");
                }
                backoff.wait(stop);
                continue;
            }
        };
        stats.opens += 1;
        tracing::info!(path = %config.path, baud = config.baud, "serial sensor opened");
        let reason = loop {
            if stop.load(Ordering::Relaxed) {
                break None;
            }
            match port.read(&mut buf) {
                Ok(0) => break Some(io::Error::from(io::ErrorKind::UnexpectedEof)),
                Ok(n) => {
                    stats.bytes_read += n as u64;
                    backoff.reset();
                    let results = decoder.push(&buf[..n]);
                    reporter.deliver(results, decoder.stats(), &mut stats, on_scan);
                }
                Err(e)
                    if matches!(
                        e.kind(),
                        io::ErrorKind::TimedOut
                            | io::ErrorKind::WouldBlock
                            | io::ErrorKind::Interrupted
                    ) => {}
                Err(e) => break Some(e),
            }
        };
        drop(port);
        let results = decoder.finish();
        reporter.deliver(results, decoder.stats(), &mut stats, on_scan);
        let Some(error) = reason else { break };
        stats.disconnects += 1;
        tracing::warn!(path = %config.path, disconnects = stats.disconnects,
            "serial sensor disconnected: {error}; reopening");
        backoff.wait(stop);
    }
    stats.decoder = *decoder.stats();
    tracing::info!(path = %config.path, "serial reader stopped: {stats}");
    Ok(stats)
}
