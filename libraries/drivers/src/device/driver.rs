//! The contract between a device driver (pure, here) and the node that owns
//! its port (bytes, line settings and time, in `nodes`).

use super::range_scan::RangeScan;
use super::stats::DeviceStats;
use super::time::{HostTime, ReadWindow};

/// What a driver asks of its port, or reports to its node, in order.
#[derive(Debug, Clone, PartialEq)]
pub enum DriverOutput {
    /// Write these bytes to the port.
    Write(Vec<u8>),
    /// Set the port's baud rate (RS-232 probing, or after a baud change
    /// command). Meaningless but harmless on USB-ACM ports.
    SetBaud(u32),
    /// Drive the port's DTR line: `true` asserts it. (RPLIDAR A1: DTR
    /// asserted stops the motor.) A port without modem lines (a pty) ignores it.
    SetDtr(bool),
    /// Discard the bytes the port has buffered but not yet handed over.
    FlushInput,
    /// A complete scan.
    Scan(RangeScan),
    /// The driver changed state.
    State(DeviceState),
    /// What the device says it is (model, firmware, serial number, geometry,
    /// supported modes), as `key = value` pairs; re-read at every handshake.
    Identity(Vec<(String, String)>),
    /// The device's own health report (RPLIDAR GET_HEALTH, SCIP II `STAT`).
    Health { ok: bool, detail: String },
    /// The link is unusable (handshake timed out, the device stopped answering,
    /// an unrecoverable device state): the node closes the port and opens it
    /// again with backoff, then calls [`DeviceDriver::connect`].
    Reconnect(String),
}

/// Where a driver is in its connect, configure, stream cycle.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum DeviceState {
    /// Port open, looking for the device (stopping a stream left running,
    /// probing baud rates, switching protocol versions).
    Connecting,
    /// The device answers; reading its identity and parameters, starting the
    /// stream.
    Configuring,
    /// Scans are arriving.
    Streaming,
    /// The device reported a fault and the driver is recovering (a reboot, a
    /// restart of the stream); the text says what happened.
    Recovering(String),
    /// The port is closed, or the driver gave up on it (waiting to reconnect).
    Disconnected,
}

impl DeviceState {
    /// A stable lower-case name for status messages.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Connecting => "connecting",
            Self::Configuring => "configuring",
            Self::Streaming => "streaming",
            Self::Recovering(_) => "recovering",
            Self::Disconnected => "disconnected",
        }
    }
}

/// A range sensor's driver. The node calls [`connect`](Self::connect) each
/// time the port opens, [`receive`](Self::receive) with every chunk of bytes
/// read (chunks split anywhere), [`poll`](Self::poll) whenever a read returns
/// nothing (at least every 50 ms) and after each `receive`, and
/// [`shutdown`](Self::shutdown) before it closes the port for good. Drivers
/// never block, never read a clock, never panic on any input, and never
/// allocate a size read from the wire without checking it against the device's
/// limits.
pub trait DeviceDriver: Send {
    /// The device kind (`hokuyo`, `rplidar`, `tfmini`, ...).
    fn kind(&self) -> &'static str;
    /// The port has just been opened (the first time or after a reconnect):
    /// forget partial input and start the handshake.
    fn connect(&mut self, now: HostTime, out: &mut Vec<DriverOutput>);
    /// Bytes read from the port; `now` is when the read returned.
    fn receive(&mut self, bytes: &[u8], now: HostTime, out: &mut Vec<DriverOutput>);
    /// Bytes read from the port, with what the node knows of when they
    /// became readable ([`ReadWindow`]). A driver of a device that sends no
    /// time bounds its readings' lateness from it; the others need only
    /// the return time, and this default passes that to
    /// [`receive`](Self::receive).
    fn receive_read(&mut self, bytes: &[u8], window: ReadWindow, out: &mut Vec<DriverOutput>) {
        self.receive(bytes, window.returned, out);
    }
    /// Time-driven decisions: reply timeouts, retries, a stalled stream.
    fn poll(&mut self, now: HostTime, out: &mut Vec<DriverOutput>);
    /// The node is stopping: what to send to leave the device quiet (laser
    /// off, stream stopped, motor off). The node writes it, waits briefly, and
    /// closes the port.
    fn shutdown(&mut self, out: &mut Vec<DriverOutput>);
    /// The current state.
    fn state(&self) -> &DeviceState;
    /// The counters so far (kept across reconnects).
    fn stats(&self) -> &DeviceStats;
}
