//! Host-to-sensor command lines (spec C-42-03320B §7 "Communication Format"
//! and §8 "Sensor Commands"): a 2-character symbol, fixed-width decimal
//! parameters, an optional `;`-separated tag the sensor echoes back, and LF.

use thiserror::Error;

/// Why a command could not be built.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum CommandError {
    #[error("tag is longer than 16 characters")]
    TagTooLong,
    #[error("tag holds a character outside A-Z a-z 0-9 space . _ + @")]
    TagCharacter,
    #[error("{name} {value} does not fit the command's {digits} decimal digits")]
    ParameterTooWide {
        name: &'static str,
        value: u32,
        digits: usize,
    },
    #[error("end step {end} is before start step {start}")]
    EndBeforeStart { start: u16, end: u16 },
}

/// The optional string a command carries after `;` and the sensor echoes:
/// at most 16 characters from `[A-Za-z0-9 ._+@]` (spec §7).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Tag(String);

impl Tag {
    /// The longest tag the spec allows.
    pub const MAX_LEN: usize = 16;

    pub fn new(text: &str) -> Result<Self, CommandError> {
        if text.len() > Self::MAX_LEN {
            return Err(CommandError::TagTooLong);
        }
        let allowed = |c: char| c.is_ascii_alphanumeric() || " ._+@".contains(c);
        if !text.chars().all(allowed) {
            return Err(CommandError::TagCharacter);
        }
        Ok(Self(text.to_owned()))
    }

    pub fn as_str(&self) -> &str {
        &self.0
    }
}

/// The `TM` control code (spec §8.6).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TimeMode {
    /// `TM0`: enter the time-adjust mode (the laser goes off).
    Enter = 0,
    /// `TM1`: read the sensor's 4-character millisecond timer.
    Read = 1,
    /// `TM2`: leave the time-adjust mode.
    Leave = 2,
}

/// The measurement commands (spec §8.1, §8.2; `ME`/`GE` are the SCIP 2.x
/// range-plus-intensity variants, `ND`/`HD`/`NE`/`HE` the multi-echo ones:
/// urg_c `urg_start_measurement()` sends `M`/`N` for streamed and `G`/`H` for
/// one-scan requests, second letter `D` ranges, `E` ranges and intensity).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ScanKind {
    /// Streamed ranges, 3 characters each.
    Md,
    /// Streamed ranges, 2 characters each (at most 4095 mm).
    Ms,
    /// Streamed range and intensity pairs, 3 + 3 characters.
    Me,
    /// One scan of ranges, 3 characters each.
    Gd,
    /// One scan of ranges, 2 characters each.
    Gs,
    /// One scan of range and intensity pairs, 3 + 3 characters.
    Ge,
    /// Streamed multi-echo ranges: up to 3 echoes per step, 3 characters
    /// each, the extra ones prefixed `&`.
    Nd,
    /// Streamed multi-echo range and intensity pairs, 3 + 3 characters per
    /// echo, the extra echoes prefixed `&`.
    Ne,
    /// One scan of multi-echo ranges (as `ND`).
    Hd,
    /// One scan of multi-echo range and intensity pairs (as `NE`).
    He,
}

impl ScanKind {
    /// The 2-character command symbol.
    pub fn symbol(self) -> &'static str {
        match self {
            Self::Md => "MD",
            Self::Ms => "MS",
            Self::Me => "ME",
            Self::Gd => "GD",
            Self::Gs => "GS",
            Self::Ge => "GE",
            Self::Nd => "ND",
            Self::Ne => "NE",
            Self::Hd => "HD",
            Self::He => "HE",
        }
    }

    /// Whether the sensor keeps sending scans (`M*`, `N*`) rather than one
    /// (`G*`, `H*`).
    pub fn is_streamed(self) -> bool {
        matches!(self, Self::Md | Self::Ms | Self::Me | Self::Nd | Self::Ne)
    }

    /// Characters per range value (spec §6: `*S` commands use 2, others 3).
    pub fn range_width(self) -> usize {
        match self {
            Self::Ms | Self::Gs => 2,
            _ => 3,
        }
    }

    /// Whether every echo carries an intensity after its range.
    pub fn has_intensity(self) -> bool {
        matches!(self, Self::Me | Self::Ge | Self::Ne | Self::He)
    }

    /// Whether a step may carry more than one echo (`N*`, `H*`; urg_c
    /// `receive_length_data()`).
    pub fn is_multiecho(self) -> bool {
        matches!(self, Self::Nd | Self::Ne | Self::Hd | Self::He)
    }

    /// The same command without intensity (`ME` to `MD`, `GE` to `GD`, `NE`
    /// to `ND`, `HE` to `HD`).
    pub fn without_intensity(self) -> Self {
        match self {
            Self::Me => Self::Md,
            Self::Ge => Self::Gd,
            Self::Ne => Self::Nd,
            Self::He => Self::Hd,
            other => other,
        }
    }

    /// The same command with one echo per step (`ND` to `MD`, `NE` to `ME`,
    /// `HD` to `GD`, `HE` to `GE`).
    pub fn without_multiecho(self) -> Self {
        match self {
            Self::Nd => Self::Md,
            Self::Ne => Self::Me,
            Self::Hd => Self::Gd,
            Self::He => Self::Ge,
            other => other,
        }
    }

    /// The most characters one step's data can take: a value group per echo
    /// and a `&` before each extra echo.
    pub fn max_step_chars(self) -> usize {
        let group = self.range_width() * if self.has_intensity() { 2 } else { 1 };
        if self.is_multiecho() {
            MAX_ECHOES * group + (MAX_ECHOES - 1)
        } else {
            group
        }
    }
}

/// The most echoes a multi-echo step carries (urg_c `URG_MAX_ECHO`).
pub const MAX_ECHOES: usize = 3;

/// A measurement request: which steps, merged how, how often.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ScanRequest {
    pub kind: ScanKind,
    /// First step (4 digits).
    pub start: u16,
    /// Last step, inclusive (4 digits).
    pub end: u16,
    /// Adjacent steps merged into one value (2 digits; the sensor reports the
    /// cluster's minimum, spec §8.1).
    pub cluster: u8,
    /// Scans skipped between two sent scans (`M*`/`N*` only, 1 digit).
    pub interval: u8,
    /// Scans to send, `0` = until `QT` (`M*`/`N*` only, 2 digits).
    pub scans: u8,
}

impl ScanRequest {
    /// Checks every parameter against its field width.
    pub fn validate(&self) -> Result<(), CommandError> {
        check_width("start step", self.start.into(), 4)?;
        check_width("end step", self.end.into(), 4)?;
        check_width("cluster count", self.cluster.into(), 2)?;
        check_width("scan interval", self.interval.into(), 1)?;
        check_width("number of scans", self.scans.into(), 2)?;
        if self.end < self.start {
            return Err(CommandError::EndBeforeStart {
                start: self.start,
                end: self.end,
            });
        }
        Ok(())
    }

    /// How many values a scan carries (for multi-echo commands: how many
    /// first echoes): the steps divided by the cluster count, rounded up (a
    /// last partial cluster still yields a value).
    pub fn value_count(&self) -> usize {
        let steps = usize::from(self.end.saturating_sub(self.start)) + 1;
        steps.div_ceil(usize::from(self.cluster.max(1)))
    }

    /// The command text without tag or terminator: `MD`/`MS`/`ME`/`ND`/`NE`
    /// start(4) end(4) cluster(2) interval(1) scans(2), or
    /// `GD`/`GS`/`GE`/`HD`/`HE` start(4) end(4) cluster(2) (urg_c
    /// `send_distance_command()`; `parse_distance_echoback()` expects 15- and
    /// 12-character echoes).
    fn text(&self) -> String {
        let base = format!(
            "{}{:04}{:04}{:02}",
            self.kind.symbol(),
            self.start,
            self.end,
            self.cluster
        );
        if self.kind.is_streamed() {
            format!("{base}{:01}{:02}", self.interval, self.scans)
        } else {
            base
        }
    }

    /// Whether `echo` is this request's echo. A streamed scan's echo carries
    /// the remaining scan count instead of the requested one (spec §8.1), so
    /// for `M*`/`N*` the last two characters only have to be digits.
    pub fn matches_echo(&self, echo: &[u8], tag: Option<&Tag>) -> bool {
        let expected = with_tag(self.text(), tag).into_bytes();
        if !self.kind.is_streamed() || expected.len() != echo.len() {
            return expected == echo;
        }
        let count_at = self.text().len().saturating_sub(2);
        echo.iter()
            .zip(&expected)
            .enumerate()
            .all(|(i, (got, want))| {
                if (count_at..count_at + 2).contains(&i) {
                    got.is_ascii_digit()
                } else {
                    got == want
                }
            })
    }
}

fn check_width(name: &'static str, value: u32, digits: usize) -> Result<(), CommandError> {
    let limit = 10u32.pow(digits as u32);
    if value < limit {
        Ok(())
    } else {
        Err(CommandError::ParameterTooWide {
            name,
            value,
            digits,
        })
    }
}

fn with_tag(text: String, tag: Option<&Tag>) -> String {
    match tag {
        Some(tag) => format!("{text};{}", tag.as_str()),
        None => text,
    }
}

/// A command the driver sends.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Command {
    /// `QT`: laser off, stop streaming (spec §8.4).
    Qt,
    /// `BM`: laser on (spec §8.3).
    Bm,
    /// `RS`: reset settings (spec §8.5).
    Rs,
    /// `RB`: reboot, sent twice (urg_c `urg_reboot()`).
    Rb,
    /// `VV`: version (spec §8.11).
    Vv,
    /// `PP`: parameters (spec §8.12).
    Pp,
    /// `II`: status (spec §8.13).
    Ii,
    /// `TM0`/`TM1`/`TM2` (spec §8.6).
    Tm(TimeMode),
    /// `SS` + 6-digit bit rate (spec §8.7).
    SetBitRate(u32),
    /// `SCIP2.0`: switch a SCIP 1.1 sensor to SCIP 2.0 (spec §2).
    Scip2,
    /// `MD`/`MS`/`ME`/`GD`/`GS`/`GE`/`ND`/`NE`/`HD`/`HE`.
    Scan(ScanRequest),
}

impl Command {
    /// The line the sensor echoes: the command text and tag, no terminator.
    pub fn echo(&self, tag: Option<&Tag>) -> Result<Vec<u8>, CommandError> {
        let text = match self {
            Self::Qt => "QT".to_owned(),
            Self::Bm => "BM".to_owned(),
            Self::Rs => "RS".to_owned(),
            Self::Rb => "RB".to_owned(),
            Self::Vv => "VV".to_owned(),
            Self::Pp => "PP".to_owned(),
            Self::Ii => "II".to_owned(),
            Self::Tm(mode) => format!("TM{}", *mode as u8),
            Self::SetBitRate(baud) => {
                check_width("bit rate", *baud, 6)?;
                format!("SS{baud:06}")
            }
            Self::Scip2 => "SCIP2.0".to_owned(),
            Self::Scan(request) => {
                request.validate()?;
                request.text()
            }
        };
        Ok(with_tag(text, tag).into_bytes())
    }

    /// The bytes to write: the echo line terminated by LF.
    pub fn to_bytes(&self, tag: Option<&Tag>) -> Result<Vec<u8>, CommandError> {
        let mut bytes = self.echo(tag)?;
        bytes.push(b'\n');
        Ok(bytes)
    }
}
