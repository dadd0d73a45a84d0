//! candump log replay: frames from a `candump -L` log file, paced by their
//! stamps (real time, optionally sped up) or as fast as the reader takes them.
//! Each frame carries the log's stamp; it is read-only (nothing sent arrives).

use super::backoff::sleep_unless_stopped;
use super::device_port::host_now;
use super::{CanSource, SourceError};
use shroud_drivers::can::{CandumpParser, CandumpRecord};
use shroud_drivers::can_device::{FrameClock, TimedFrame};
use shroud_drivers::DecoderStats;
use std::fs::File;
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

/// How fast a log is replayed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ReplayPace {
    /// Each frame as soon as it is asked for.
    AsFastAsPossible,
    /// Frames spaced as their stamps say, divided by `speed` (1.0 = real time).
    RealTime { speed: f64 },
}

/// A log being replayed.
#[derive(Debug)]
pub struct CandumpReplay {
    path: PathBuf,
    lines: std::io::Lines<BufReader<File>>,
    parser: CandumpParser,
    pace: ReplayPace,
    interface: Option<String>,
    /// The next record, read but not yet due.
    next: Option<CandumpRecord>,
    /// Wall-clock instant of the first frame and its stamp.
    origin: Option<(Instant, u64)>,
}

impl CandumpReplay {
    /// Opens `path`. With `interface`, only frames logged on that interface are
    /// replayed. A missing or unreadable file is [`SourceError::Fatal`].
    pub fn open(
        path: &Path,
        pace: ReplayPace,
        interface: Option<&str>,
    ) -> Result<Self, SourceError> {
        if let ReplayPace::RealTime { speed } = pace {
            if !(speed.is_finite() && speed > 0.0) {
                return Err(SourceError::Fatal(format!(
                    "replay speed {speed} must be positive"
                )));
            }
        }
        let file = File::open(path).map_err(|e| {
            SourceError::Fatal(format!("cannot open candump log {}: {e}", path.display()))
        })?;
        Ok(Self {
            path: path.to_owned(),
            lines: BufReader::new(file).lines(),
            parser: CandumpParser::default(),
            pace,
            interface: interface.map(str::to_owned),
            next: None,
            origin: None,
        })
    }

    /// The next record of the selected interface, skipping (and counting) bad lines.
    fn read_record(&mut self) -> Result<Option<CandumpRecord>, SourceError> {
        loop {
            let line = match self.lines.next() {
                None => return Ok(None),
                Some(Ok(line)) => line,
                Some(Err(e)) => {
                    return Err(SourceError::Fatal(format!(
                        "reading {}: {e}",
                        self.path.display()
                    )))
                }
            };
            match self.parser.push_line(&line) {
                None => {}
                Some(Err(error)) => tracing::debug!(path = %self.path.display(), "{error}"),
                Some(Ok(record))
                    if self
                        .interface
                        .as_ref()
                        .is_none_or(|i| *i == record.interface) =>
                {
                    return Ok(Some(record));
                }
                Some(Ok(_)) => {}
            }
        }
    }
}

impl CanSource for CandumpReplay {
    fn recv(&mut self, timeout: Duration) -> Result<Option<TimedFrame>, SourceError> {
        let record = match self.next.take() {
            Some(r) => r,
            None => match self.read_record()? {
                Some(r) => r,
                None => return Err(SourceError::Finished(self.name())),
            },
        };
        let ReplayPace::RealTime { speed } = self.pace else {
            return Ok(Some(logged(&record)));
        };
        let (start, first) = *self.origin.get_or_insert((Instant::now(), record.stamp_ns));
        let offset = record.stamp_ns.saturating_sub(first) as f64 / speed;
        let due = start + Duration::from_secs_f64(offset / 1e9);
        let wait = due.saturating_duration_since(Instant::now());
        let never = AtomicBool::new(false);
        if wait > timeout {
            sleep_unless_stopped(timeout, &never);
            self.next = Some(record);
            return Ok(None);
        }
        sleep_unless_stopped(wait, &never);
        Ok(Some(logged(&record)))
    }

    fn name(&self) -> String {
        format!("candump:{}", self.path.display())
    }

    fn transport_stats(&self) -> DecoderStats {
        *self.parser.stats()
    }
}

/// A logged frame with the log's stamp, read now.
fn logged(record: &CandumpRecord) -> TimedFrame {
    TimedFrame {
        frame: record.frame,
        stamp_ns: record.stamp_ns,
        clock: FrameClock::Log,
        received: host_now(),
    }
}
