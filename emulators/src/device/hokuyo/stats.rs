//! Counters of what the emulator did and of every input it rejected, each
//! rejection under a stable snake_case kind name.

/// Why a command line was answered with an error status (or dropped).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rejection {
    /// Unknown command symbol (`0E`).
    UnknownCommand,
    /// Fewer parameter characters than the command needs (`0C`).
    MissingParameters,
    /// Parameters followed by something other than `;string` (`0D`).
    ExtraCharacters,
    /// A parameter failed the command's own check (`01`..`07`, `10`).
    BadParameter,
    /// `;string` longer than 16 characters (`0G`).
    TagTooLong,
    /// `;string` with a character outside `[A-Za-z0-9 ._+@]` (`0H`).
    TagInvalid,
    /// A line longer than the input buffer (`0B`).
    LineTooLong,
    /// A command refused in the sensor's current state (TM `02`/`03`/`04`,
    /// GD/GS/GE/HD/HE `10` laser off, SS `03`/`04`).
    WrongState,
    /// A command other than TM while in time-adjust mode (`0E`).
    TimeAdjustMode,
    /// A command refused because the sensor is in the abnormal state (`0L`).
    Abnormal,
    /// A SCIP 2.0 command sent while the sensor speaks SCIP 1.1 (`E`).
    Scip11Mode,
    /// Bytes that arrived while the sensor was rebooting (ignored; counted
    /// per byte).
    Rebooting,
}

impl Rejection {
    /// Every kind, in a fixed order.
    pub const ALL: [Rejection; 12] = [
        Rejection::UnknownCommand,
        Rejection::MissingParameters,
        Rejection::ExtraCharacters,
        Rejection::BadParameter,
        Rejection::TagTooLong,
        Rejection::TagInvalid,
        Rejection::LineTooLong,
        Rejection::WrongState,
        Rejection::TimeAdjustMode,
        Rejection::Abnormal,
        Rejection::Scip11Mode,
        Rejection::Rebooting,
    ];

    /// The stable snake_case name of this kind.
    pub fn name(self) -> &'static str {
        match self {
            Rejection::UnknownCommand => "unknown_command",
            Rejection::MissingParameters => "missing_parameters",
            Rejection::ExtraCharacters => "extra_characters",
            Rejection::BadParameter => "bad_parameter",
            Rejection::TagTooLong => "tag_too_long",
            Rejection::TagInvalid => "tag_invalid",
            Rejection::LineTooLong => "line_too_long",
            Rejection::WrongState => "wrong_state",
            Rejection::TimeAdjustMode => "time_adjust_mode",
            Rejection::Abnormal => "abnormal",
            Rejection::Scip11Mode => "scip11_mode",
            Rejection::Rebooting => "rebooting",
        }
    }

    fn index(self) -> usize {
        self as usize
    }
}

/// What the emulator has done since it was created.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct HokuyoStats {
    /// Command lines received (empty lines excluded).
    pub commands: u64,
    /// Scan messages sent (MD/MS/ME/ND/NE scans and GD/GS/GE/HD/HE replies).
    pub scans_sent: u64,
    /// Stream scans skipped because the RS-232 line was still sending the
    /// previous output when they were measured.
    pub scans_skipped_link_busy: u64,
    /// Stream scans skipped because the output buffer was full (nobody
    /// polled) or too much time passed in one step.
    pub scans_skipped_output_full: u64,
    /// Reply bytes dropped because the output buffer was full.
    pub bytes_dropped_output_full: u64,
    rejected: [u64; Rejection::ALL.len()],
}

impl HokuyoStats {
    /// How many inputs were rejected for `kind`.
    pub fn rejected(&self, kind: Rejection) -> u64 {
        self.rejected.get(kind.index()).copied().unwrap_or(0)
    }

    /// Every rejection kind's name with its count.
    pub fn rejections(&self) -> impl Iterator<Item = (&'static str, u64)> + '_ {
        Rejection::ALL
            .iter()
            .map(|&kind| (kind.name(), self.rejected(kind)))
    }

    pub(crate) fn count_rejection(&mut self, kind: Rejection) {
        if let Some(count) = self.rejected.get_mut(kind.index()) {
            *count = count.saturating_add(1);
        }
    }
}
