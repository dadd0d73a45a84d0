//! What the integrator chooses for a Hokuyo SCIP 2.0 sensor: the link, the
//! measurement command and its parameters, and the timeouts.

use std::time::Duration;

use super::command::ScanKind;

/// How the sensor is attached.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub enum Link {
    /// USB CDC-ACM (`/dev/ttyACM*`): the baud rate is irrelevant and never set.
    #[default]
    Usb,
    /// RS-232: the driver tries these baud rates in order, sending `QT` at
    /// each and waiting `reply_timeout` (urg_c `connect_urg_device()` tries
    /// 19200, 38400, 115200). An empty list means [`Link::DEFAULT_BAUDS`].
    Rs232 { bauds: Vec<u32> },
}

impl Link {
    /// The URG-04LX RS-232 default (19200) first, then the other rates urg_c
    /// probes.
    pub const DEFAULT_BAUDS: [u32; 3] = [19_200, 38_400, 115_200];

    /// RS-232 with the default probe order.
    pub fn rs232() -> Self {
        Self::Rs232 {
            bauds: Self::DEFAULT_BAUDS.to_vec(),
        }
    }
}

/// Which measurement command the driver runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ScanCommand {
    /// `MD`: streamed, 3-character ranges.
    #[default]
    Md,
    /// `MS`: streamed, 2-character ranges (at most 4095 mm).
    Ms,
    /// `ME`: streamed ranges with intensity (falls back to `MD` when the
    /// sensor rejects it).
    Me,
    /// `GD`: one scan per request, polled (the driver sends the next `GD` as
    /// soon as a reply is in).
    Gd,
    /// `ND`: streamed multi-echo ranges, up to 3 echoes per step, each its
    /// own ray (`NE` with `intensity`). Falls back to `MD` (`ME`) when the
    /// sensor rejects it.
    Nd,
    /// `HD`: one multi-echo scan per request, polled like `GD` (`HE` with
    /// `intensity`). Falls back to `GD` (`GE`) when the sensor rejects it.
    Hd,
}

/// Configuration of a [`ScipDriver`](super::ScipDriver).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ScipConfig {
    /// Default [`Link::Usb`].
    pub link: Link,
    /// RS-232 only: after the handshake, switch the sensor and the port to
    /// this rate with `SS` (spec C-42-03320B §8.7). It is also probed, last,
    /// on later connects. Default `None`.
    pub target_baud: Option<u32>,
    /// Default [`ScanCommand::Md`].
    pub scan: ScanCommand,
    /// First step; `None` = `AMIN` from `PP`. Clamped to `AMIN..=AMAX`.
    pub start_step: Option<u16>,
    /// Last step; `None` = `AMAX` from `PP`. Clamped to `start..=AMAX`.
    pub end_step: Option<u16>,
    /// Adjacent steps merged per ray (per echo for `ND`/`HD`), clamped to
    /// 1..=99. Default 1.
    pub cluster: u8,
    /// Scans skipped between sent scans (`MD`/`MS`/`ME`/`ND`/`NE`), clamped
    /// to 0..=9. Default 0.
    pub interval: u8,
    /// Ask for intensity: `MD` becomes `ME`, `GD` becomes `GE`, `ND` becomes
    /// `NE`, `HD` becomes `HE`. When the sensor rejects it the driver falls
    /// back, counts `intensity_unsupported` and says so in its Identity; it
    /// asks again on every connect. Ignored for `MS`. Default `false`.
    pub intensity: bool,
    /// How long to wait for the reply to a command. Default 1 s.
    pub reply_timeout: Duration,
    /// How long streaming may go without a delivered scan before the driver
    /// asks for a reconnect; `None` = max(3 scan periods including skipped
    /// scans plus the scan's transfer time at the RS-232 rate, 500 ms).
    pub stream_timeout: Option<Duration>,
    /// `TM1` round trips per connect for the clock offset; 0 = no sync
    /// (stamps from arrival times). Default 5.
    pub tm_round_trips: u8,
}

impl Default for ScipConfig {
    fn default() -> Self {
        Self {
            link: Link::Usb,
            target_baud: None,
            scan: ScanCommand::Md,
            start_step: None,
            end_step: None,
            cluster: 1,
            interval: 0,
            intensity: false,
            reply_timeout: Duration::from_secs(1),
            stream_timeout: None,
            tm_round_trips: 5,
        }
    }
}

impl ScipConfig {
    /// The wire command the configuration asks for first.
    pub(super) fn scan_kind(&self) -> ScanKind {
        match (self.scan, self.intensity) {
            (ScanCommand::Md, false) => ScanKind::Md,
            (ScanCommand::Md | ScanCommand::Me, _) => ScanKind::Me,
            (ScanCommand::Ms, _) => ScanKind::Ms,
            (ScanCommand::Gd, false) => ScanKind::Gd,
            (ScanCommand::Gd, true) => ScanKind::Ge,
            (ScanCommand::Nd, false) => ScanKind::Nd,
            (ScanCommand::Nd, true) => ScanKind::Ne,
            (ScanCommand::Hd, false) => ScanKind::Hd,
            (ScanCommand::Hd, true) => ScanKind::He,
        }
    }

    /// The baud rates to probe on RS-232 (the target rate appended when not
    /// listed), or `None` on USB.
    pub(super) fn probe_bauds(&self) -> Option<Vec<u32>> {
        let Link::Rs232 { bauds } = &self.link else {
            return None;
        };
        let mut bauds = if bauds.is_empty() {
            Link::DEFAULT_BAUDS.to_vec()
        } else {
            bauds.clone()
        };
        if let Some(target) = self.target_baud.filter(|t| !bauds.contains(t)) {
            bauds.push(target);
        }
        Some(bauds)
    }
}
