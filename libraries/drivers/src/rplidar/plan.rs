//! Which scan to start: the choice among the configured mode, what the
//! device reported (`GET_LIDAR_CONF`, `GET_SAMPLERATE`) and what this driver
//! decodes; the request that starts it and the descriptor it must answer.
//!
//! The SDK's rules (`startScan`, `startScanNormal_commonpath`,
//! `startScanExpress` in `sl_lidar_driver.cpp`): a mode whose answer type is
//! 0x81 is started with `SCAN`; any other with `EXPRESS_SCAN` whose
//! working mode is the mode id on devices that answer `GET_LIDAR_CONF`, and
//! 0 (legacy express) on older ones. Sample durations come from the mode's
//! `US_PER_SAMPLE`, else `GET_SAMPLERATE`, else the SDK's 476 µs.

use super::conf::{LidarConf, ScanModeInfo};
use super::config::ScanMode;
use super::descriptor::{Descriptor, SendMode};
use super::protocol::{answer, cmd, LEGACY_SAMPLE_US};
use super::replies::{DeviceInfo, SampleRate};
use super::request;
use super::stream::SampleFormat;

/// How the scan is started.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StartCommand {
    Scan,
    Express { working_mode: u8 },
}

/// The scan the driver starts.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ScanPlan {
    pub command: StartCommand,
    pub format: SampleFormat,
    /// The mode's name (the device's, when it has one).
    pub name: String,
    /// Sample duration, µs in q8.
    pub sample_us_q8: u32,
}

impl ScanPlan {
    /// The request that starts the scan.
    pub fn request(&self) -> Vec<u8> {
        match self.command {
            StartCommand::Scan => request::encode(cmd::SCAN, &[]),
            StartCommand::Express { working_mode } => request::express_scan(working_mode),
        }
    }

    /// Whether `descriptor` announces this scan's stream.
    pub fn expects(&self, descriptor: &Descriptor) -> bool {
        descriptor.mode == SendMode::Multiple
            && descriptor.answer_type == self.format.answer_type()
            && descriptor.len as usize == self.format.packet_len()
    }

    /// For `Identity`.
    pub fn describe(&self) -> String {
        let command = match self.command {
            StartCommand::Scan => "SCAN".to_string(),
            StartCommand::Express { working_mode } => format!("EXPRESS_SCAN mode {working_mode}"),
        };
        format!(
            "{} ({} samples, {command}, {:.1} us/sample)",
            self.name,
            self.format.name(),
            f64::from(self.sample_us_q8) / 256.0
        )
    }
}

/// What the handshake learned that the choice depends on.
#[derive(Debug, Clone, Copy)]
pub struct Capabilities<'a> {
    pub info: &'a DeviceInfo,
    pub rate: Option<SampleRate>,
    pub conf: &'a LidarConf,
}

/// The plan, and whether the configured mode was unavailable (the driver
/// then runs `Auto`'s choice and counts `unsupported_scan_mode`).
pub fn choose(mode: ScanMode, caps: Capabilities<'_>) -> (ScanPlan, bool) {
    let wanted = match mode {
        ScanMode::Standard => Some(standard(caps)),
        ScanMode::Express => express(caps),
        ScanMode::Dense => listed(caps, answer::DENSE_CAPSULED),
        ScanMode::Auto => return (auto(caps), false),
    };
    match wanted {
        Some(plan) => (plan, false),
        None => (auto(caps), true),
    }
}

fn auto(caps: Capabilities<'_>) -> ScanPlan {
    let typical = caps
        .conf
        .typical
        .and_then(|id| caps.conf.mode(id))
        .and_then(|m| from_mode(m, caps));
    typical
        .or_else(|| express(caps))
        .unwrap_or_else(|| standard(caps))
}

/// A listed express mode; on devices without a mode list, legacy express
/// when the firmware has it.
fn express(caps: Capabilities<'_>) -> Option<ScanPlan> {
    if !caps.conf.modes.is_empty() {
        return listed(caps, answer::CAPSULED);
    }
    caps.info.supports_express().then(|| ScanPlan {
        command: StartCommand::Express { working_mode: 0 },
        format: SampleFormat::Express,
        name: "Express".to_string(),
        sample_us_q8: rate_q8(caps.rate.map(|r| r.express_us)),
    })
}

fn standard(caps: Capabilities<'_>) -> ScanPlan {
    listed(caps, answer::MEASUREMENT).unwrap_or_else(|| ScanPlan {
        command: StartCommand::Scan,
        format: SampleFormat::Standard,
        name: "Standard".to_string(),
        sample_us_q8: rate_q8(caps.rate.map(|r| r.standard_us)),
    })
}

fn listed(caps: Capabilities<'_>, answer_type: u8) -> Option<ScanPlan> {
    caps.conf
        .mode_with_answer(answer_type)
        .and_then(|m| from_mode(m, caps))
}

/// The plan for a listed mode, if its answer type is decoded here.
fn from_mode(mode: &ScanModeInfo, caps: Capabilities<'_>) -> Option<ScanPlan> {
    let format = SampleFormat::from_answer_type(mode.answer_type?)?;
    let command = match format {
        SampleFormat::Standard => StartCommand::Scan,
        _ => StartCommand::Express {
            working_mode: u8::try_from(mode.id).ok()?,
        },
    };
    let fallback_us = caps.rate.map(|r| match format {
        SampleFormat::Standard => r.standard_us,
        _ => r.express_us,
    });
    Some(ScanPlan {
        command,
        format,
        name: mode
            .name
            .clone()
            .unwrap_or_else(|| format.name().to_string()),
        sample_us_q8: mode
            .us_per_sample_q8
            .filter(|&us| us > 0)
            .unwrap_or_else(|| rate_q8(fallback_us)),
    })
}

fn rate_q8(us: Option<u16>) -> u32 {
    let us = us.filter(|&us| us > 0).map_or(LEGACY_SAMPLE_US, u32::from);
    us << 8
}
