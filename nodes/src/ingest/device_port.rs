//! The port under a device driver: opens a serial device, carries bytes both
//! ways, applies the line settings the driver asks for, hands the driver the
//! host's time, and reopens the port with backoff when it goes away or the
//! driver gives up on it. Every decision about the device is the driver's
//! (`shroud_drivers::device`); this file only moves bytes.

use super::backoff::{Backoff, BackoffConfig};
use super::ReaderError;
use crate::transport::{monotonic_ns, unix_ns};
use serialport::{ClearBuffer, SerialPort};
use shroud_drivers::device::{DeviceDriver, DeviceStats, DriverOutput, HostTime, ReadWindow};
use std::io;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

/// Where the device is and how long the port may block.
#[derive(Debug, Clone, PartialEq)]
pub struct DevicePortConfig {
    /// Device path (`/dev/ttyACM0`, `/dev/serial/by-id/...`, a pty).
    pub path: String,
    /// The rate the port opens at (the driver may change it).
    pub baud: u32,
    /// Longest a read blocks; the driver is polled at least this often. A
    /// device that sends no time of its own is dated by the reads around
    /// its bytes ([`ReadWindow`]): the shorter this, the tighter.
    pub read_timeout: Duration,
    pub backoff: BackoffConfig,
    /// How long the port stays open after the driver's shutdown bytes.
    pub shutdown_grace: Duration,
}

impl DevicePortConfig {
    pub fn new(path: &str, baud: u32) -> Self {
        Self {
            path: path.to_owned(),
            baud,
            read_timeout: Duration::from_millis(20),
            backoff: BackoffConfig::default(),
            shutdown_grace: Duration::from_millis(100),
        }
    }
}

/// What the port itself counted (the driver counts the rest).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct PortStats {
    pub opens: u64,
    pub open_failures: u64,
    /// The device went away (read or write error, hang-up).
    pub disconnects: u64,
    /// The driver asked for a reconnect.
    pub reconnects: u64,
    /// Line settings the port could not apply (DTR on a pty, a baud rate the
    /// adapter refuses).
    pub line_setting_failures: u64,
}

/// The host's time now, on both clocks.
pub fn host_now() -> HostTime {
    HostTime::new(monotonic_ns(), unix_ns())
}

/// Why one session with the port ended.
enum Ended {
    Stopped,
    Lost(io::Error),
    Reconnect(String),
}

/// Runs `driver` on the serial device of `config` until `stop` is set.
///
/// Blocking: run it on its own thread. Each output the driver produces that
/// is not about the port (scans, state, identity, health) goes to `on_output`
/// with the driver's and the port's counters. On stop the driver's shutdown
/// bytes are written and the port is held open for `shutdown_grace`.
pub fn run_device(
    config: &DevicePortConfig,
    driver: &mut dyn DeviceDriver,
    on_output: &mut dyn FnMut(DriverOutput, &DeviceStats, &PortStats),
    stop: &AtomicBool,
) -> Result<PortStats, ReaderError> {
    if config.baud == 0 || config.path.is_empty() || config.read_timeout.is_zero() {
        return Err(ReaderError::Config(format!(
            "a device port needs a path, a baud rate and a read timeout (got {:?}, {}, {:?})",
            config.path, config.baud, config.read_timeout
        )));
    }
    let mut stats = PortStats::default();
    let mut backoff = Backoff::new(config.backoff);
    while !stop.load(Ordering::Relaxed) {
        let mut port = match open(config) {
            Ok(port) => port,
            Err(error) => {
                stats.open_failures += 1;
                if stats.open_failures.is_power_of_two() {
                    tracing::warn!(path = %config.path, attempts = stats.open_failures,
                        "cannot open {} device: {error}; retrying", driver.kind());
                }
                backoff.wait(stop);
                continue;
            }
        };
        stats.opens += 1;
        tracing::info!(path = %config.path, "{} device port open", driver.kind());
        let mut session = Session {
            port: port.as_mut(),
            driver: &mut *driver,
            stats: &mut stats,
            on_output: &mut *on_output,
            path: &config.path,
        };
        let ended = session.run(stop);
        match ended {
            Ended::Stopped => {
                session.shut_down(config.shutdown_grace);
                break;
            }
            Ended::Lost(error) => {
                stats.disconnects += 1;
                tracing::warn!(path = %config.path, disconnects = stats.disconnects,
                    "{} device lost: {error}; reopening", driver.kind());
            }
            Ended::Reconnect(reason) => {
                stats.reconnects += 1;
                backoff.reset();
                tracing::warn!(path = %config.path, "{} device: {reason}; reopening the port",
                    driver.kind());
            }
        }
        drop(port);
        let (kind, device_stats) = (driver.kind(), driver.stats().clone());
        on_output(
            DriverOutput::State(shroud_drivers::device::DeviceState::Disconnected),
            &device_stats,
            &stats,
        );
        tracing::debug!("{kind} device: {device_stats}");
        backoff.wait(stop);
    }
    Ok(stats)
}

fn open(config: &DevicePortConfig) -> serialport::Result<Box<dyn SerialPort>> {
    let port = serialport::new(&config.path, config.baud)
        .timeout(config.read_timeout)
        .open()?;
    Ok(port)
}

/// One open port and its driver.
struct Session<'a> {
    port: &'a mut dyn SerialPort,
    driver: &'a mut dyn DeviceDriver,
    stats: &'a mut PortStats,
    on_output: &'a mut dyn FnMut(DriverOutput, &DeviceStats, &PortStats),
    path: &'a str,
}

impl Session<'_> {
    fn run(&mut self, stop: &AtomicBool) -> Ended {
        let mut outputs = Vec::new();
        self.driver.connect(host_now(), &mut outputs);
        if let Some(ended) = self.apply(&mut outputs) {
            return ended;
        }
        let mut buf = vec![0u8; 8192];
        // When the previous read was called: it took every byte readable
        // then, so the next read's bytes became readable later. Unknown
        // before the first read, and after a read that filled the buffer.
        let mut previous_call: Option<HostTime> = None;
        loop {
            if stop.load(Ordering::Relaxed) {
                return Ended::Stopped;
            }
            let called = host_now();
            match self.port.read(&mut buf) {
                Ok(0) => return Ended::Lost(io::ErrorKind::UnexpectedEof.into()),
                Ok(n) => {
                    let window = ReadWindow {
                        after: previous_call,
                        returned: host_now(),
                    };
                    self.driver.receive_read(&buf[..n], window, &mut outputs);
                    previous_call = (n < buf.len()).then_some(called);
                }
                Err(e) if is_quiet(&e) => previous_call = Some(called),
                Err(e) => return Ended::Lost(e),
            }
            self.driver.poll(host_now(), &mut outputs);
            if let Some(ended) = self.apply(&mut outputs) {
                return ended;
            }
        }
    }

    /// Carries out the driver's outputs in order. After one that ends the
    /// session (a failed write, a reconnect) the port actions are skipped and
    /// the rest still reach the node; the first end is returned.
    fn apply(&mut self, outputs: &mut Vec<DriverOutput>) -> Option<Ended> {
        let mut ended = None;
        for output in outputs.drain(..) {
            if ended.is_some() {
                // The port is done for; what the driver reported still counts.
                if !is_port_action(&output) {
                    (self.on_output)(output, self.driver.stats(), self.stats);
                }
                continue;
            }
            match output {
                DriverOutput::Write(bytes) => {
                    let written = self.port.write_all(&bytes).and_then(|()| self.port.flush());
                    if let Err(e) = written {
                        ended = Some(Ended::Lost(e));
                    }
                }
                DriverOutput::SetBaud(baud) => {
                    let set = self.port.set_baud_rate(baud);
                    self.line_setting("baud rate", set);
                }
                DriverOutput::SetDtr(level) => {
                    let set = self.port.write_data_terminal_ready(level);
                    self.line_setting("DTR", set);
                }
                DriverOutput::FlushInput => {
                    let cleared = self.port.clear(ClearBuffer::Input);
                    self.line_setting("input flush", cleared);
                }
                DriverOutput::Reconnect(reason) => ended = Some(Ended::Reconnect(reason)),
                other => (self.on_output)(other, self.driver.stats(), self.stats),
            }
        }
        ended
    }

    fn line_setting(&mut self, what: &str, result: serialport::Result<()>) {
        if let Err(error) = result {
            self.stats.line_setting_failures += 1;
            // A pty has no modem lines: expected, so not worth a warning each time.
            if self.stats.line_setting_failures == 1 {
                tracing::warn!(
                    path = self.path,
                    "cannot set {what}: {error} (counted in line_setting_failures)"
                );
            } else {
                tracing::debug!(path = self.path, "cannot set {what}: {error}");
            }
        }
    }

    /// Sends the driver's shutdown bytes and gives them time to leave.
    fn shut_down(&mut self, grace: Duration) {
        let mut outputs = Vec::new();
        self.driver.shutdown(&mut outputs);
        if let Some(Ended::Lost(e)) = self.apply(&mut outputs) {
            tracing::warn!(
                path = self.path,
                "{} device: shutdown not delivered: {e}",
                self.driver.kind()
            );
            return;
        }
        std::thread::sleep(grace);
        tracing::info!(path = self.path, "{} device left quiet", self.driver.kind());
    }
}

/// Outputs the port carries out itself (the rest go to the node).
fn is_port_action(output: &DriverOutput) -> bool {
    matches!(
        output,
        DriverOutput::Write(_)
            | DriverOutput::SetBaud(_)
            | DriverOutput::SetDtr(_)
            | DriverOutput::FlushInput
            | DriverOutput::Reconnect(_)
    )
}

fn is_quiet(e: &io::Error) -> bool {
    matches!(
        e.kind(),
        io::ErrorKind::TimedOut | io::ErrorKind::WouldBlock | io::ErrorKind::Interrupted
    )
}
