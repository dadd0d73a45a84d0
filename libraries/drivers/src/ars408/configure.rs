//! Sending the RadarConfiguration (0x200) on connect and confirming it by
//! the RadarState (0x201) that follows: what was asked must be what the
//! radar reports, else the frame is resent, and after the last resend the
//! driver streams anyway and says in its health what did not take.

use super::config::{RadarOutput, RadarSettings};
use super::error::Ars408Error;
use super::layout::{configuration, Bound};
use super::radar_state::{output_type_name, RadarState};
use crate::can::CanFrame;
use crate::device::HostTime;

/// Without a confirming RadarState this long after a send, the frame is sent
/// again.
pub const CONFIG_RETRY_NS: u64 = 1_000_000_000;
/// Resends after the first send; one retry period after the last one the
/// driver gives up (`config_not_confirmed`).
pub const CONFIG_RESENDS: u32 = 3;

/// Where the configuration is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Progress {
    /// Not started (no settings, or not writable), or stopped.
    Idle,
    /// Sent, waiting for a matching RadarState.
    Waiting {
        last_sent: HostTime,
        resends: u32,
    },
    Confirmed,
    GaveUp,
}

/// What a poll decided.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) enum Retry {
    Nothing,
    Resend(CanFrame),
    GiveUp,
}

#[derive(Debug, Clone, PartialEq)]
pub(super) struct Configurator {
    output: RadarOutput,
    settings: RadarSettings,
    frame: CanFrame,
    pub progress: Progress,
}

impl Configurator {
    /// Encodes the frame once, so that a DBC that cannot carry the settings
    /// fails at start.
    pub fn new(
        bound: &Bound<14>,
        output: RadarOutput,
        settings: RadarSettings,
    ) -> Result<Self, Ars408Error> {
        let frame = encode(bound, output, &settings).map_err(Ars408Error::Configuration)?;
        Ok(Self {
            output,
            settings,
            frame,
            progress: Progress::Idle,
        })
    }

    /// The frame to send now (connect).
    pub fn start(&mut self, now: HostTime) -> CanFrame {
        self.progress = Progress::Waiting {
            last_sent: now,
            resends: 0,
        };
        self.frame
    }

    pub fn stop(&mut self) {
        self.progress = Progress::Idle;
    }

    pub fn waiting(&self) -> bool {
        matches!(self.progress, Progress::Waiting { .. })
    }

    pub fn poll(&mut self, now: HostTime) -> Retry {
        let Progress::Waiting { last_sent, resends } = self.progress else {
            return Retry::Nothing;
        };
        if now.since(last_sent) < CONFIG_RETRY_NS {
            return Retry::Nothing;
        }
        if resends < CONFIG_RESENDS {
            self.progress = Progress::Waiting {
                last_sent: now,
                resends: resends + 1,
            };
            Retry::Resend(self.frame)
        } else {
            self.progress = Progress::GaveUp;
            Retry::GiveUp
        }
    }

    /// What the radar reports differently from what was asked, one phrase
    /// each (empty: all took).
    pub fn mismatches(&self, state: &RadarState) -> Vec<String> {
        let s = &self.settings;
        let mut out = Vec::new();
        if state.output_type != self.output.code() {
            out.push(format!(
                "output type {} (radar reports {})",
                self.output.name(),
                output_type_name(state.output_type)
            ));
        }
        if let Some(m) = s.max_distance_m {
            // MaxDistanceCfg has 2 m steps: within 1 m is the same setting.
            if (state.max_distance_m - f64::from(m)).abs() >= 1.0 {
                out.push(format!(
                    "max distance {m} m (radar reports {} m)",
                    state.max_distance_m
                ));
            }
        }
        let flags = [
            ("send quality", s.send_quality, state.send_quality),
            ("send ext info", s.send_ext_info, state.send_ext_info),
            (
                "rcs threshold high",
                s.rcs_threshold_high,
                state.rcs_threshold == 1,
            ),
        ];
        for (name, asked, reported) in flags {
            if asked.is_some_and(|a| a != reported) {
                out.push(format!("{name} {} (radar reports {reported})", !reported));
            }
        }
        let codes = [
            ("radar power", s.radar_power, state.radar_power),
            ("sort index", s.sort_index, state.sort_index),
        ];
        for (name, asked, reported) in codes {
            if let Some(a) = asked.filter(|a| u32::from(*a) != reported) {
                out.push(format!("{name} {a} (radar reports {reported})"));
            }
        }
        out
    }
}

/// The 0x200 frame: the output type and each given setting with its
/// `*_valid` bit; every other signal of the message at raw 0.
fn encode(
    bound: &Bound<14>,
    output: RadarOutput,
    s: &RadarSettings,
) -> Result<CanFrame, crate::dbc::DbcError> {
    let flag = |b: bool| if b { 1.0 } else { 0.0 };
    let pair = |v: Option<f64>| (flag(v.is_some()), v.unwrap_or(0.0));
    let fields = [
        (1.0, f64::from(output.code())),
        pair(s.max_distance_m.map(f64::from)),
        pair(s.send_quality.map(flag)),
        pair(s.send_ext_info.map(flag)),
        pair(s.radar_power.map(f64::from)),
        pair(s.sort_index.map(f64::from)),
        pair(s.rcs_threshold_high.map(flag)),
    ];
    let mut values: Vec<(&str, f64)> = bound
        .spec
        .signals
        .iter()
        .map(|signal| (signal.name.as_str(), raw_zero(signal)))
        .collect();
    let names = configuration::NAMES;
    for (k, (valid, value)) in fields.into_iter().enumerate() {
        // The last value given for a name wins (MessageSpec::encode).
        values.extend([(names[2 * k], valid), (names[2 * k + 1], value)]);
    }
    bound.spec.encode(&values)
}

/// The physical value of raw 0 (clamped into the signal's range, if any).
fn raw_zero(signal: &crate::dbc::SignalSpec) -> f64 {
    if signal.has_range() {
        signal
            .offset
            .clamp(signal.min.min(signal.max), signal.max.max(signal.min))
    } else {
        signal.offset
    }
}
