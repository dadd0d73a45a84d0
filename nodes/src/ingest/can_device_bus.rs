//! The bus under a CAN device driver: opens a [`CanSource`], hands the driver
//! every frame with its times, sends what the driver asks, polls it when the
//! bus is quiet, and reopens the source with backoff when it goes away. Every
//! decision about the device is the driver's
//! (`shroud_drivers::can_device`); this file only moves frames.

use super::backoff::{Backoff, BackoffConfig};
use super::can_source::open_with_backoff;
use super::device_port::host_now;
use super::{CanSource, ReaderError, SourceError};
use shroud_drivers::can_device::{CanDeviceDriver, CanDriverOutput};
use shroud_drivers::DecoderStats;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

/// What the bus itself counted (the driver counts the rest).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct BusStats {
    pub opens: u64,
    pub open_failures: u64,
    /// The source went away (adapter unplugged, interface down).
    pub disconnects: u64,
    pub frames_received: u64,
    pub frames_sent: u64,
    /// Frames the driver asked to send that the source could not carry (a
    /// log replay is read-only; a write failed).
    pub frames_unsent: u64,
    /// The transport's own decoding (SLCAN or candump lines), summed over
    /// every opening.
    pub transport: DecoderStats,
}

/// What the bus hands its node: a driver output, or (`None`) only a chance
/// to read the counters, at least every 50 ms and after every failed open.
pub type OnCanOutput<'a> = dyn FnMut(Option<CanDriverOutput>, &dyn CanDeviceDriver, &BusStats) + 'a;

/// Runs `driver` on the sources `open` makes until `stop` is set or a source
/// finishes (the end of a log). Every output other than a send goes to
/// `on_output` with the driver (for its counters) and the bus's counters.
/// Failed opens and disconnects are logged, counted and retried with backoff
/// (reset once a reopened source delivers a frame); [`SourceError::Fatal`]
/// returns an error.
pub fn run_can_device(
    open: &mut dyn FnMut() -> Result<Box<dyn CanSource>, SourceError>,
    driver: &mut dyn CanDeviceDriver,
    backoff: BackoffConfig,
    on_output: &mut OnCanOutput<'_>,
    stop: &AtomicBool,
) -> Result<BusStats, ReaderError> {
    let mut stats = BusStats::default();
    let mut backoff = Backoff::new(backoff);
    let mut outputs = Vec::new();
    while !stop.load(Ordering::Relaxed) {
        let mut failures = stats.open_failures;
        let opened = open_with_backoff(open, &mut failures, &mut backoff, stop, &mut |n| {
            let now = BusStats {
                open_failures: n,
                ..stats
            };
            on_output(None, &*driver, &now);
        })?;
        stats.open_failures = failures;
        let Some(mut source) = opened else {
            break;
        };
        stats.opens += 1;
        let name = source.name();
        tracing::info!(source = %name, writable = source.writable(), "CAN bus opened");
        driver.connect(host_now(), source.writable(), &mut outputs);
        let mut session = Session {
            source: &mut *source,
            transport_before: stats.transport,
            backoff: &mut backoff,
        };
        let outcome = session.serve(driver, &mut stats, &mut outputs, on_output, stop);
        drop(source);
        // The driver reports its own Disconnected state.
        driver.disconnect(&mut outputs);
        deliver(&mut outputs, None, driver, &mut stats, on_output);
        match outcome {
            Ok(()) => break,
            Err(SourceError::Finished(_)) => {
                tracing::info!(source = %name, "CAN source finished");
                break;
            }
            Err(SourceError::Fatal(message)) => return Err(SourceError::Fatal(message).into()),
            Err(error) => {
                stats.disconnects += 1;
                tracing::warn!(source = %name, disconnects = stats.disconnects, "{error}; reopening");
                on_output(None, driver, &stats);
                backoff.wait(stop);
            }
        }
    }
    Ok(stats)
}

/// One opening of the source.
struct Session<'a> {
    source: &'a mut dyn CanSource,
    /// The transport counters of the earlier openings.
    transport_before: DecoderStats,
    backoff: &'a mut Backoff,
}

impl Session<'_> {
    /// Frames in, outputs out, until the stop or a source error.
    fn serve(
        &mut self,
        driver: &mut dyn CanDeviceDriver,
        stats: &mut BusStats,
        outputs: &mut Vec<CanDriverOutput>,
        on_output: &mut OnCanOutput<'_>,
        stop: &AtomicBool,
    ) -> Result<(), SourceError> {
        let poll = Duration::from_millis(50);
        deliver(outputs, Some(&mut *self.source), driver, stats, on_output);
        let mut heard = false;
        while !stop.load(Ordering::Relaxed) {
            let received = self.source.recv(poll);
            // Live transport counters (bad SLCAN lines, NAKs, candump lines).
            stats.transport = self.transport_before;
            stats.transport.merge(&self.source.transport_stats());
            if let Some(frame) = received? {
                stats.frames_received += 1;
                if !heard {
                    // A source that opens and then fails at once (an
                    // interface that is down) keeps its backoff growing.
                    heard = true;
                    self.backoff.reset();
                }
                driver.receive(&frame, outputs);
            }
            driver.poll(host_now(), outputs);
            deliver(outputs, Some(&mut *self.source), driver, stats, on_output);
            on_output(None, driver, stats);
        }
        Ok(())
    }
}

/// Sends the driver's frames (when there is a bus to send them on) and hands
/// the rest to `on_output`, in order.
fn deliver(
    outputs: &mut Vec<CanDriverOutput>,
    mut source: Option<&mut dyn CanSource>,
    driver: &dyn CanDeviceDriver,
    stats: &mut BusStats,
    on_output: &mut OnCanOutput<'_>,
) {
    for output in outputs.drain(..) {
        match output {
            CanDriverOutput::Send(frame) => {
                let sent = match source.as_deref_mut() {
                    Some(bus) if bus.writable() => bus.send(&frame),
                    _ => Err(SourceError::Fatal("no writable bus".into())),
                };
                match sent {
                    Ok(()) => stats.frames_sent += 1,
                    Err(error) => {
                        stats.frames_unsent += 1;
                        tracing::warn!("CAN frame {:#x} not sent: {error}", frame.id);
                    }
                }
            }
            other => on_output(Some(other), driver, stats),
        }
    }
}
