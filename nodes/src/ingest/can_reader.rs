//! The CAN range-sensor reader: pulls frames from any [`CanSource`], assembles
//! scans with the CAN sensor protocol decoder, and reopens the source with
//! backoff when it disconnects. [`CanSourceSpec`] names a source in text, for
//! command lines and configuration files.

use super::backoff::{Backoff, BackoffConfig};
use super::can_source::open_with_backoff;
use super::candump_source::{CandumpReplay, ReplayPace};
use super::report::ErrorReporter;
use super::slcan_source::SlcanSource;
use super::socketcan_source::SocketCanSource;
use super::{CanSource, ReaderError, ReaderStats, SourceError};
use shroud_drivers::can::slcan::{bitrate_code, BITRATES};
use shroud_drivers::can::{CanScanDecoder, CanSensorConfig};
use shroud_drivers::can_device::FrameClock;
use shroud_drivers::Scan;
use std::path::PathBuf;
use std::str::FromStr;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

/// How to read a CAN range sensor.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct CanReaderConfig {
    /// The sensor's ids.
    pub sensor: CanSensorConfig,
    pub backoff: BackoffConfig,
}

/// Reads scans of one CAN range sensor (`docs/sensor-protocols.md` §2) until `stop` is set
/// or the source finishes.
///
/// Blocking, like [`run_serial_reader`](super::run_serial_reader). `open` makes
/// a new source; it is called at the start and after every disconnect. Failed
/// opens ([`SourceError::Open`]) and disconnects are logged, counted and retried
/// with backoff; [`SourceError::Finished`] (end of a log, bus gone) returns the
/// counters; [`SourceError::Fatal`] returns an error. Frames of other devices
/// are counted as `unknown_id` and logged only at `trace`.
pub fn run_can_reader(
    open: &mut dyn FnMut() -> Result<Box<dyn CanSource>, SourceError>,
    config: &CanReaderConfig,
    on_scan: &mut dyn FnMut(Scan, &ReaderStats),
    stop: &AtomicBool,
) -> Result<ReaderStats, ReaderError> {
    let mut stats = ReaderStats::default();
    let mut decoder = CanScanDecoder::new(config.sensor);
    let mut reporter = ErrorReporter::new("can");
    let mut backoff = Backoff::new(config.backoff);
    let poll = Duration::from_millis(100);
    let mut finished = false;
    while !finished && !stop.load(Ordering::Relaxed) {
        let opened = open_with_backoff(
            open,
            &mut stats.open_failures,
            &mut backoff,
            stop,
            &mut |_| {},
        )?;
        let Some(mut source) = opened else {
            break;
        };
        stats.opens += 1;
        let name = source.name();
        tracing::info!(source = %name, "CAN source opened");
        let transport_before = stats.transport;
        let outcome = loop {
            if stop.load(Ordering::Relaxed) {
                break Ok(());
            }
            match source.recv(poll) {
                Ok(Some(timed)) => {
                    stats.frames_received += 1;
                    backoff.reset();
                    let results = decoder.push(&timed.frame);
                    reporter.deliver(results, decoder.stats(), &mut stats, on_scan);
                }
                Ok(None) => {}
                Err(error) => break Err(error),
            }
            stats.transport = transport_before;
            stats.transport.merge(&source.transport_stats());
        };
        stats.transport = transport_before;
        stats.transport.merge(&source.transport_stats());
        drop(source);
        let results = decoder.finish();
        reporter.deliver(results, decoder.stats(), &mut stats, on_scan);
        match outcome {
            Ok(()) => break,
            Err(SourceError::Finished(_)) => {
                tracing::info!(source = %name, "CAN source finished");
                finished = true;
            }
            Err(SourceError::Fatal(message)) => return Err(SourceError::Fatal(message).into()),
            Err(error) => {
                stats.disconnects += 1;
                tracing::warn!(source = %name, disconnects = stats.disconnects, "{error}; reopening");
                backoff.wait(stop);
            }
        }
    }
    stats.decoder = *decoder.stats();
    tracing::info!("CAN reader stopped: {stats}");
    Ok(stats)
}

/// A CAN source named in text:
///
/// - `socketcan:IFACE` (e.g. `socketcan:can0`);
/// - `slcan:PATH[@BAUD][:BITRATE]` (e.g. `slcan:/dev/ttyACM0@115200:500000`;
///   without a bitrate nothing is sent to the adapter);
/// - `candump:PATH[@SPEED]` replays a log in real time times SPEED, or with
///   `@max` as fast as possible (e.g. `candump:/tmp/run.log@2`).
#[derive(Debug, Clone, PartialEq)]
pub enum CanSourceSpec {
    SocketCan {
        interface: String,
    },
    Slcan {
        path: String,
        baud: u32,
        bitrate: Option<u32>,
    },
    Candump {
        path: PathBuf,
        pace: ReplayPace,
        interface: Option<String>,
    },
}

impl CanSourceSpec {
    /// Checks what can be checked before opening: a log file exists.
    pub fn check(&self) -> Result<(), String> {
        match self {
            Self::Candump { path, .. } if !path.is_file() => {
                Err(format!("candump log {} does not exist", path.display()))
            }
            _ => Ok(()),
        }
    }

    /// Which clock the frames' stamps are on.
    pub fn clock(&self) -> FrameClock {
        match self {
            Self::SocketCan { .. } => FrameClock::Kernel,
            Self::Slcan { .. } => FrameClock::HostReceipt,
            Self::Candump { .. } => FrameClock::Log,
        }
    }

    /// Opens the source this names.
    pub fn open(&self) -> Result<Box<dyn CanSource>, SourceError> {
        Ok(match self {
            Self::SocketCan { interface } => Box::new(SocketCanSource::open(interface)?),
            Self::Slcan {
                path,
                baud,
                bitrate,
            } => Box::new(SlcanSource::open(path, *baud, *bitrate)?),
            Self::Candump {
                path,
                pace,
                interface,
            } => Box::new(CandumpReplay::open(path, *pace, interface.as_deref())?),
        })
    }
}

impl FromStr for CanSourceSpec {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        let (kind, rest) = s
            .split_once(':')
            .ok_or_else(|| format!("{s:?}: expected socketcan:IFACE, slcan:PATH[@BAUD][:BITRATE] or candump:PATH[@SPEED|@max]"))?;
        let number = |t: &str, what: &str| {
            t.parse::<u32>()
                .map_err(|_| format!("{s:?}: bad {what} {t:?}"))
        };
        match kind {
            "socketcan" if !rest.is_empty() => Ok(Self::SocketCan {
                interface: rest.to_owned(),
            }),
            "slcan" => {
                let (path_baud, bitrate) = match rest.rsplit_once(':') {
                    Some((p, b)) if b.bytes().all(|c| c.is_ascii_digit()) && !b.is_empty() => {
                        (p, Some(number(b, "bitrate")?))
                    }
                    _ => (rest, None),
                };
                let (path, baud) = match path_baud.rsplit_once('@') {
                    Some((p, b)) => (p, number(b, "baud rate")?),
                    None => (path_baud, 115_200),
                };
                if path.is_empty() {
                    return Err(format!("{s:?}: no serial port path"));
                }
                if let Some(bps) = bitrate.filter(|&b| bitrate_code(b).is_none()) {
                    return Err(format!(
                        "{s:?}: {bps} bit/s is not an SLCAN bitrate (one of {BITRATES:?})"
                    ));
                }
                Ok(Self::Slcan {
                    path: path.to_owned(),
                    baud,
                    bitrate,
                })
            }
            "candump" => {
                let (path, pace) = match rest.rsplit_once('@') {
                    Some((p, "max")) => (p, ReplayPace::AsFastAsPossible),
                    Some((p, speed)) => {
                        let speed: f64 = speed
                            .parse()
                            .ok()
                            .filter(|v: &f64| v.is_finite() && *v > 0.0)
                            .ok_or_else(|| format!("{s:?}: bad replay speed {speed:?}"))?;
                        (p, ReplayPace::RealTime { speed })
                    }
                    None => (rest, ReplayPace::RealTime { speed: 1.0 }),
                };
                if path.is_empty() {
                    return Err(format!("{s:?}: no log path"));
                }
                Ok(Self::Candump {
                    path: path.into(),
                    pace,
                    interface: None,
                })
            }
            _ => Err(format!("{s:?}: expected socketcan:IFACE, slcan:PATH[@BAUD][:BITRATE] or candump:PATH[@SPEED|@max]")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ingest_source_specs_parse() {
        assert_eq!(
            "socketcan:vcan0".parse::<CanSourceSpec>(),
            Ok(CanSourceSpec::SocketCan {
                interface: "vcan0".into()
            })
        );
        assert_eq!(
            "slcan:/dev/ttyACM0@921600:500000".parse::<CanSourceSpec>(),
            Ok(CanSourceSpec::Slcan {
                path: "/dev/ttyACM0".into(),
                baud: 921_600,
                bitrate: Some(500_000)
            })
        );
        assert_eq!(
            "slcan:/dev/pts/3".parse::<CanSourceSpec>(),
            Ok(CanSourceSpec::Slcan {
                path: "/dev/pts/3".into(),
                baud: 115_200,
                bitrate: None
            })
        );
        assert_eq!(
            "candump:/tmp/a.log@max".parse::<CanSourceSpec>(),
            Ok(CanSourceSpec::Candump {
                path: "/tmp/a.log".into(),
                pace: ReplayPace::AsFastAsPossible,
                interface: None
            })
        );
        assert_eq!(
            "candump:a.log@2.5".parse::<CanSourceSpec>(),
            Ok(CanSourceSpec::Candump {
                path: "a.log".into(),
                pace: ReplayPace::RealTime { speed: 2.5 },
                interface: None
            })
        );
        for bad in [
            "can0",
            "socketcan:",
            "slcan:@9600",
            "slcan:/dev/x@fast",
            "slcan:/dev/x:50001",
            "candump:a@0",
            "candump:@max",
            "x:y",
        ] {
            assert!(bad.parse::<CanSourceSpec>().is_err(), "{bad}");
        }
    }
}
