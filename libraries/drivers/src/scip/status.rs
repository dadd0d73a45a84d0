//! The 2-character status of a reply and what it means (spec C-42-03320B
//! §8.1 `MD`/`MS` codes, §8.2 `GD` code `10`, §9 "Response to Invalid
//! Commands"; `0L` abnormal state from seqsense/urg_stamped `src/urg_stamped.cpp`
//! `cbRB`/error handling and issue #70). Some codes mean different things for
//! different commands (`BM` `02` = laser already on); the command handlers
//! decide which codes they accept, this only names the generic meaning.

use super::sum::line_sum;

/// A reply's status code, e.g. `*b"00"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Status(pub [u8; 2]);

/// Why a status line was rejected.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StatusLineError {
    /// Not two characters and a sum.
    Malformed,
    /// The sum character does not match.
    BadChecksum,
}

impl StatusLineError {
    /// The error-counter name.
    pub fn kind(self) -> &'static str {
        match self {
            Self::Malformed => "malformed_reply",
            Self::BadChecksum => "bad_checksum",
        }
    }
}

/// The generic meaning of a status code.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StatusClass {
    /// `00`: command received without error.
    Ok,
    /// `99`: a streamed scan follows.
    Streaming,
    /// `98`: processing resumed after the sensor confirmed normal laser
    /// operation (after a hardware fault).
    Resumed,
    /// `01`..`09`: a parameter of the command is wrong (per command).
    ParameterError,
    /// `10`: `GD`/`GS` asked while the laser is off.
    LaserOff,
    /// `21`..`49`: processing stopped to verify an error.
    Verifying,
    /// `50`..`97`: hardware trouble (laser, motor).
    HardwareFault,
    /// `0L`: the sensor is in its abnormal state; `RB` twice reboots it.
    Abnormal,
    /// `0D`, `0E`: undefined command (the model does not have it).
    Unsupported,
    /// `0A`..`0C`, `0F`..`0H`: the command could not be processed (internal
    /// error, repeated command, missing parameters, bad tag).
    InvalidCommand,
    /// `0I`: the sensor is in firmware update mode.
    FirmwareUpdate,
    /// Anything else.
    Other,
}

impl Status {
    /// `00`.
    pub const OK: Status = Status(*b"00");

    /// Parses a status line: two characters and their sum (`00P`, `99b`).
    pub fn parse(line: &[u8]) -> Result<Self, StatusLineError> {
        let [a, b, sum] = line else {
            return Err(StatusLineError::Malformed);
        };
        if line_sum(&[*a, *b]) != *sum {
            return Err(StatusLineError::BadChecksum);
        }
        Ok(Self([*a, *b]))
    }

    /// The code as text.
    pub fn code(&self) -> String {
        String::from_utf8_lossy(&self.0).into_owned()
    }

    /// Whether the code is one of `codes`.
    pub fn is_any(&self, codes: &[&[u8; 2]]) -> bool {
        codes.iter().any(|c| **c == self.0)
    }

    /// The generic meaning.
    pub fn class(&self) -> StatusClass {
        match self.number() {
            Some(0) => StatusClass::Ok,
            Some(1..=9) => StatusClass::ParameterError,
            Some(10) => StatusClass::LaserOff,
            Some(21..=49) => StatusClass::Verifying,
            Some(50..=97) => StatusClass::HardwareFault,
            Some(98) => StatusClass::Resumed,
            Some(99) => StatusClass::Streaming,
            Some(_) => StatusClass::Other,
            None => match &self.0 {
                b"0L" => StatusClass::Abnormal,
                b"0D" | b"0E" => StatusClass::Unsupported,
                b"0A" | b"0B" | b"0C" | b"0F" | b"0G" | b"0H" => StatusClass::InvalidCommand,
                b"0I" => StatusClass::FirmwareUpdate,
                _ => StatusClass::Other,
            },
        }
    }

    /// The code as a number when both characters are digits.
    fn number(&self) -> Option<u8> {
        let [a, b] = self.0;
        (a.is_ascii_digit() && b.is_ascii_digit()).then(|| (a - b'0') * 10 + (b - b'0'))
    }

    /// The error-counter name for this status when a command fails with it.
    pub fn error_kind(&self) -> &'static str {
        self.class().error_kind()
    }

    /// `"<code> (<meaning>)"` for log texts and reasons.
    pub fn describe(&self) -> String {
        format!("{} ({})", self.code(), self.class().meaning())
    }
}

impl StatusClass {
    /// The error-counter name (`device_error_<class>`).
    pub fn error_kind(self) -> &'static str {
        match self {
            Self::Ok | Self::Streaming => "device_error",
            Self::Resumed => "device_resumed",
            Self::ParameterError => "device_error_parameter",
            Self::LaserOff => "device_error_laser_off",
            Self::Verifying => "device_error_verifying",
            Self::HardwareFault => "device_error_hardware",
            Self::Abnormal => "device_error_abnormal",
            Self::Unsupported => "device_error_unsupported",
            Self::InvalidCommand => "device_error_invalid_command",
            Self::FirmwareUpdate => "device_error_firmware_update",
            Self::Other => "device_error",
        }
    }

    /// A short English meaning.
    pub fn meaning(self) -> &'static str {
        match self {
            Self::Ok => "ok",
            Self::Streaming => "scan data",
            Self::Resumed => "resumed after an error",
            Self::ParameterError => "parameter error",
            Self::LaserOff => "laser off",
            Self::Verifying => "stopped to verify an error",
            Self::HardwareFault => "hardware trouble",
            Self::Abnormal => "abnormal state",
            Self::Unsupported => "undefined command",
            Self::InvalidCommand => "invalid command",
            Self::FirmwareUpdate => "firmware update mode",
            Self::Other => "unknown status",
        }
    }
}
