//! Decodes the data part of a scan reply (spec C-42-03320B §8.1, §8.2): the
//! 4-character timestamp line, then data lines of at most 64 characters, each
//! with its own sum. Values straddle line boundaries, so the lines are
//! stripped of their sums and concatenated before they are cut into 2- or
//! 3-character groups (urg_c `receive_length_data()` keeps a carry buffer for
//! the same reason). `ME`/`GE` send each step as range then intensity.

use super::command::ScanRequest;
use super::echoes::split_echoes;
use super::encoding::decode;
use super::scan_error::ScanDataError;
use super::sum::strip_sum;

/// The most characters in one data line before its sum (spec §8.1).
pub const MAX_DATA_LINE: usize = 64;

/// One decoded scan: the sensor's timestamp and one value per cluster (per
/// echo for multi-echo commands).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ScanData {
    /// The sensor's 24-bit millisecond timer when it took the scan.
    pub timestamp_ms: u32,
    /// Ranges in mm (or error codes below `DMIN`), in step order; for
    /// multi-echo commands each step's echoes in wire order, first echo first.
    pub ranges: Vec<u32>,
    /// Intensities, one per range, for `ME`/`GE`/`NE`/`HE`.
    pub intensities: Option<Vec<u32>>,
    /// Multi-echo commands only: how many echoes (1 to 3) each step has, in
    /// step order; they add up to `ranges.len()`.
    pub echoes: Option<Vec<u8>>,
}

/// Decodes `lines` (the reply's lines after its status line: the timestamp
/// line, then data lines) for `request`.
pub fn decode_scan(lines: &[Vec<u8>], request: &ScanRequest) -> Result<ScanData, ScanDataError> {
    let (stamp_line, data_lines) = lines.split_first().ok_or(ScanDataError::BadTimestamp)?;
    let timestamp_ms = decode_timestamp(stamp_line)?;
    let text = join_data_lines(data_lines)?;
    let range_width = request.kind.range_width();
    let group = if request.kind.has_intensity() {
        2 * range_width
    } else {
        range_width
    };
    let steps = request.value_count();
    let (groups, echoes) = if request.kind.is_multiecho() {
        let split = split_echoes(&text, group, steps)?;
        (split.groups, Some(split.echo_counts))
    } else {
        check_length(&text, steps.saturating_mul(group))?;
        (text, None)
    };
    let values = groups
        .chunks_exact(range_width)
        .map(decode)
        .collect::<Option<Vec<u32>>>()
        .ok_or(ScanDataError::BadCharacter)?;
    let (ranges, intensities) = split_values(values, request.kind.has_intensity());
    Ok(ScanData {
        timestamp_ms,
        ranges,
        intensities,
        echoes,
    })
}

fn check_length(text: &[u8], expected: usize) -> Result<(), ScanDataError> {
    if text.len() == expected {
        Ok(())
    } else {
        Err(ScanDataError::WrongLength {
            expected,
            got: text.len(),
        })
    }
}

/// Decodes a timestamp line: 4 characters and their sum (also the `TM1`
/// reply's time line, spec §8.6).
pub fn decode_timestamp(line: &[u8]) -> Result<u32, ScanDataError> {
    let body = strip_sum(line).ok_or(ScanDataError::BadChecksum)?;
    if body.len() != 4 {
        return Err(ScanDataError::BadTimestamp);
    }
    decode(body).ok_or(ScanDataError::BadCharacter)
}

fn join_data_lines(lines: &[Vec<u8>]) -> Result<Vec<u8>, ScanDataError> {
    let mut text = Vec::with_capacity(lines.len().saturating_mul(MAX_DATA_LINE));
    for line in lines {
        let body = strip_sum(line).ok_or(ScanDataError::BadChecksum)?;
        if body.len() > MAX_DATA_LINE {
            return Err(ScanDataError::LongLine);
        }
        text.extend_from_slice(body);
    }
    Ok(text)
}

/// Ranges, and intensities when every value is a (range, intensity) pair.
fn split_values(values: Vec<u32>, with_intensity: bool) -> (Vec<u32>, Option<Vec<u32>>) {
    if !with_intensity {
        return (values, None);
    }
    let (ranges, intensities) = values
        .chunks_exact(2)
        .filter_map(|pair| match pair {
            [range, intensity] => Some((*range, *intensity)),
            _ => None,
        })
        .unzip();
    (ranges, Some(intensities))
}
