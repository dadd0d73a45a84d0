//! Parsing and checking one SCIP 2.0 command line: the 2-character symbol,
//! fixed-width decimal parameters and the optional `;string` (spec §7,
//! p. 9), with the error statuses of §8 and §9.

use super::model::ModelSpec;
use super::stats::Rejection;
use super::status::{self, Status};

/// How scan values are encoded.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum DataEncoding {
    /// MS/GS: 2 characters per range (12 bits).
    TwoChar,
    /// MD/GD/HD/ND: 3 characters per range.
    ThreeChar,
    /// ME/GE/HE/NE: 3 characters of range then 3 of intensity.
    WithIntensity,
}

/// How a scan's values are sent.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct DataFormat {
    pub(crate) encoding: DataEncoding,
    /// HD/ND/HE/NE: every echo of a step, the further ones each prefixed
    /// `&` (urg_c `receive_length_data()`).
    pub(crate) multi_echo: bool,
}

/// The steps a scan covers and how they are grouped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct ScanRequest {
    pub(crate) format: DataFormat,
    pub(crate) start: u32,
    pub(crate) end: u32,
    /// Steps merged into one value, at least 1 (a request's 0 means 1).
    pub(crate) cluster: u32,
}

/// An MD/MS/ME/ND/NE request.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct StreamRequest {
    pub(crate) scan: ScanRequest,
    /// Revolutions skipped between two sent scans.
    pub(crate) interval: u32,
    /// Scans to send; 0 = until stopped.
    pub(crate) scans: u32,
}

/// The TM control code (spec §8.6, p. 15).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum TimeControl {
    AdjustOn,
    Read,
    AdjustOff,
}

/// A well-formed command.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Command {
    Version,
    Parameters,
    Info,
    LaserOn,
    Quit,
    Reset,
    Reboot,
    Time(TimeControl),
    /// SS with its 6-digit bit rate (checked against the model later).
    BitRate(u32),
    Stream(StreamRequest),
    Single(ScanRequest),
}

/// Why a line is refused: the status to answer and the counted kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Refusal {
    pub(crate) status: Status,
    pub(crate) kind: Rejection,
}

const fn refuse(status: Status, kind: Rejection) -> Refusal {
    Refusal { status, kind }
}

/// Longest `;string` (spec §7, p. 9).
const MAX_TAG: usize = 16;

/// The command symbols, each with its number of parameter characters.
const SYMBOLS: [(&[u8; 2], usize); 19] = [
    (b"VV", 0),
    (b"PP", 0),
    (b"II", 0),
    (b"BM", 0),
    (b"QT", 0),
    (b"RS", 0),
    (b"RB", 0),
    (b"TM", 1),
    (b"SS", 6),
    (b"MD", 13),
    (b"MS", 13),
    (b"ME", 13),
    (b"GD", 10),
    (b"GS", 10),
    (b"GE", 10),
    (b"ND", 13),
    (b"NE", 13),
    (b"HD", 10),
    (b"HE", 10),
];

/// The line's command symbol if it is one this model knows: intensity
/// (ME/GE/HE/NE) and multi-echo (HD/ND/HE/NE) commands only on models that
/// have them.
pub(crate) fn known_symbol(line: &[u8], spec: &ModelSpec) -> Option<[u8; 2]> {
    let symbol = [*line.first()?, *line.get(1)?];
    let known = SYMBOLS.iter().any(|(s, _)| **s == symbol);
    let supported = data_format(symbol).is_none_or(|format| {
        let intensity_ok = spec.has_intensity || format.encoding != DataEncoding::WithIntensity;
        intensity_ok && (spec.has_multi_echo || !format.multi_echo)
    });
    (known && supported).then_some(symbol)
}

/// The data format of a scan command (urg_c `parse_distance_parameter()`):
/// the second letter gives the encoding (S 2 characters, D 3, E 3 + 3 of
/// intensity), a first letter H or N multi-echo. `None` for other commands
/// (HS, for one, is the sensitivity command, spec §8.9).
fn data_format(symbol: [u8; 2]) -> Option<DataFormat> {
    let [kind, data] = symbol;
    let multi_echo = match kind {
        b'M' | b'G' => false,
        b'N' | b'H' => true,
        _ => return None,
    };
    let encoding = match (data, multi_echo) {
        (b'S', false) => DataEncoding::TwoChar,
        (b'D', _) => DataEncoding::ThreeChar,
        (b'E', _) => DataEncoding::WithIntensity,
        _ => return None,
    };
    Some(DataFormat {
        encoding,
        multi_echo,
    })
}

/// Parses and checks `line` for a sensor of `spec`.
pub(crate) fn parse(line: &[u8], spec: &ModelSpec) -> Result<Command, Refusal> {
    let symbol =
        known_symbol(line, spec).ok_or(refuse(status::UNDEFINED, Rejection::UnknownCommand))?;
    let params_len = SYMBOLS
        .iter()
        .find(|(s, _)| **s == symbol)
        .map_or(0, |(_, len)| *len);
    let (body, tag) = split_tag(line);
    let params = body.get(2..).unwrap_or_default();
    if params.len() < params_len {
        return Err(refuse(status::TOO_SHORT, Rejection::MissingParameters));
    }
    if params.len() > params_len {
        return Err(refuse(status::EXTRA_CHARACTERS, Rejection::ExtraCharacters));
    }
    check_tag(tag)?;
    parse_parameters(symbol, params, spec)
}

/// Splits at the first ';' into the command body and the string after it.
fn split_tag(line: &[u8]) -> (&[u8], Option<&[u8]>) {
    match line.iter().position(|&b| b == b';') {
        Some(at) => (line.get(..at).unwrap_or_default(), line.get(at + 1..)),
        None => (line, None),
    }
}

/// String characters: at most 16 of `[A-Za-z0-9 ._+@]` (spec §7, p. 9).
fn check_tag(tag: Option<&[u8]>) -> Result<(), Refusal> {
    let Some(tag) = tag else { return Ok(()) };
    if tag.len() > MAX_TAG {
        return Err(refuse(status::TAG_TOO_LONG, Rejection::TagTooLong));
    }
    let allowed = |b: &u8| b.is_ascii_alphanumeric() || b" ._+@".contains(b);
    if !tag.iter().all(allowed) {
        return Err(refuse(status::TAG_INVALID, Rejection::TagInvalid));
    }
    Ok(())
}

fn parse_parameters(symbol: [u8; 2], params: &[u8], spec: &ModelSpec) -> Result<Command, Refusal> {
    match &symbol {
        b"VV" => Ok(Command::Version),
        b"PP" => Ok(Command::Parameters),
        b"II" => Ok(Command::Info),
        b"BM" => Ok(Command::LaserOn),
        b"QT" => Ok(Command::Quit),
        b"RS" => Ok(Command::Reset),
        b"RB" => Ok(Command::Reboot),
        b"TM" => parse_time(params),
        b"SS" => decimal(params)
            .map(Command::BitRate)
            .ok_or(bad(status::CODE_01)),
        _ => parse_scan_command(symbol, params, spec),
    }
}

/// M*/N* stream scans, G*/H* send one (urg_c `send_distance_command()`:
/// single-scan letters G/H, continuous M/N).
fn parse_scan_command(
    symbol: [u8; 2],
    params: &[u8],
    spec: &ModelSpec,
) -> Result<Command, Refusal> {
    let undefined = refuse(status::UNDEFINED, Rejection::UnknownCommand);
    let format = data_format(symbol).ok_or(undefined)?;
    match symbol[0] {
        b'M' | b'N' => parse_stream(format, params, spec),
        b'G' | b'H' => parse_scan(format, params, spec).map(Command::Single),
        _ => Err(undefined),
    }
}

const fn bad(status: Status) -> Refusal {
    refuse(status, Rejection::BadParameter)
}

/// TM control code 0/1/2, else status 01 (spec §8.6, p. 15).
fn parse_time(params: &[u8]) -> Result<Command, Refusal> {
    match params {
        b"0" => Ok(Command::Time(TimeControl::AdjustOn)),
        b"1" => Ok(Command::Time(TimeControl::Read)),
        b"2" => Ok(Command::Time(TimeControl::AdjustOff)),
        _ => Err(bad(status::CODE_01)),
    }
}

/// MD/MS/ME/ND/NE: start(4) end(4) cluster(2) interval(1) scans(2),
/// statuses 01..07 (spec §8.1, p. 11; ND/NE as MD: urg_c
/// `send_distance_command()` formats them alike).
fn parse_stream(format: DataFormat, params: &[u8], spec: &ModelSpec) -> Result<Command, Refusal> {
    let (scan_params, rest) = params.split_at(params.len().min(10));
    let scan = parse_scan_fields(format, scan_params)?;
    let interval = field(rest, 0, 1).ok_or(bad(status::CODE_06))?;
    let scans = field(rest, 1, 2).ok_or(bad(status::CODE_07))?;
    check_steps(&scan, spec)?;
    Ok(Command::Stream(StreamRequest {
        scan,
        interval,
        scans,
    }))
}

/// GD/GS/GE/HD/HE: start(4) end(4) cluster(2), statuses 01..05 (spec
/// §8.2, p. 13).
fn parse_scan(format: DataFormat, params: &[u8], spec: &ModelSpec) -> Result<ScanRequest, Refusal> {
    let scan = parse_scan_fields(format, params)?;
    check_steps(&scan, spec)?;
    Ok(scan)
}

fn parse_scan_fields(format: DataFormat, params: &[u8]) -> Result<ScanRequest, Refusal> {
    let start = field(params, 0, 4).ok_or(bad(status::CODE_01))?;
    let end = field(params, 4, 4).ok_or(bad(status::CODE_02))?;
    let cluster = field(params, 8, 2).ok_or(bad(status::CODE_03))?;
    Ok(ScanRequest {
        format,
        start,
        end,
        cluster: cluster.max(1),
    })
}

/// Steps must lie within AMIN..AMAX (04) and end >= start (05).
fn check_steps(scan: &ScanRequest, spec: &ModelSpec) -> Result<(), Refusal> {
    if scan.end > spec.amax || scan.start < spec.amin {
        return Err(bad(status::CODE_04));
    }
    if scan.end < scan.start {
        return Err(bad(status::CODE_05));
    }
    Ok(())
}

/// The decimal number in `bytes[at..at + len]`, if it is all digits.
fn field(bytes: &[u8], at: usize, len: usize) -> Option<u32> {
    decimal(bytes.get(at..at.checked_add(len)?)?)
}

/// A string of 1..=9 ASCII digits as a number.
fn decimal(digits: &[u8]) -> Option<u32> {
    if digits.is_empty() || digits.len() > 9 || !digits.iter().all(u8::is_ascii_digit) {
        return None;
    }
    Some(
        digits
            .iter()
            .fold(0u32, |acc, &d| acc * 10 + u32::from(d - b'0')),
    )
}
