//! The configuration plan run at every connect: which commands, in which
//! order, and which reply answers each. The plan is sent one step at a time,
//! each waiting for its reply (or its timeout) before the next.

use super::command::{id, Command};
use super::config::{BenewakeConfig, DistanceUnit};
use super::reply::Reply;

/// One command of the plan.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Step {
    /// Ask for the firmware version; its reply proves the device listens.
    Version,
    /// Set the frame rate (only if configured).
    FrameRate(u16),
    /// Select the standard 9-byte frame in this unit (always: a device saved
    /// in another format would otherwise be misread).
    OutputFormat(DistanceUnit),
    /// Enable output (always: a device saved with output disabled is silent).
    OutputEnable,
    /// Save settings to flash (only if configured).
    Save,
}

impl Step {
    /// The command this step sends.
    pub fn command(self) -> Command {
        match self {
            Self::Version => Command::Version,
            Self::FrameRate(hz) => Command::FrameRate(hz),
            Self::OutputFormat(unit) => Command::OutputFormat(unit),
            Self::OutputEnable => Command::OutputEnable(true),
            Self::Save => Command::Save,
        }
    }

    /// Whether `reply` answers this step. A frame-rate echo answers whatever
    /// rate it reports (the device may round it); a format echo must carry the
    /// requested format; an output echo must say enabled.
    pub fn answered_by(self, reply: &Reply) -> bool {
        match (self, reply) {
            (Self::Version, Reply::Version(_)) => true,
            (Self::FrameRate(_), Reply::FrameRate(_)) => true,
            (Self::OutputFormat(unit), Reply::OutputFormat(code)) => *code == unit.format_code(),
            (Self::OutputEnable, Reply::OutputEnable(on)) => *on,
            (Self::Save, Reply::Status { command, .. }) => *command == id::SAVE,
            _ => false,
        }
    }
}

/// The steps for `config`: none for the original TFmini (no commands);
/// otherwise version, frame rate (if set), output format, output enable, save
/// (if set).
pub fn plan(config: &BenewakeConfig) -> Vec<Step> {
    if !config.model.has_commands() {
        return Vec::new();
    }
    let mut steps = vec![Step::Version];
    steps.extend(config.frame_rate.map(Step::FrameRate));
    steps.push(Step::OutputFormat(config.effective_unit()));
    steps.push(Step::OutputEnable);
    if config.save {
        steps.push(Step::Save);
    }
    steps
}
