//! The key/value replies of `VV`, `PP` and `II` (spec C-42-03320B §8.11 to
//! §8.13): each data line is `KEY:VALUE;` and a sum. `PP` gives the sensor's
//! geometry ([`ScipGeometry`]), `II` its state (`STAT`).

use thiserror::Error;

use super::sum::strip_parameter_sum;

/// Why a key/value reply was rejected.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum ParamError {
    #[error("a parameter line has a wrong sum")]
    BadChecksum,
    #[error("a parameter line is not KEY:VALUE;")]
    Malformed,
    #[error("PP lacks {0}")]
    Missing(&'static str),
    #[error("PP value {key} = {value} is not usable")]
    Invalid { key: &'static str, value: String },
}

impl ParamError {
    /// The error-counter name.
    pub fn kind(&self) -> &'static str {
        match self {
            Self::BadChecksum => "bad_checksum",
            _ => "malformed_reply",
        }
    }
}

/// Parses the data lines of a `VV`/`PP`/`II` reply (the lines after the
/// status line) into `(key, value)` pairs, in order. Any bad line rejects the
/// whole reply.
pub fn parse_pairs(lines: &[Vec<u8>]) -> Result<Vec<(String, String)>, ParamError> {
    lines.iter().map(|line| parse_pair(line)).collect()
}

fn parse_pair(line: &[u8]) -> Result<(String, String), ParamError> {
    let body = strip_parameter_sum(line).ok_or(ParamError::BadChecksum)?;
    let body = body.strip_suffix(b";").ok_or(ParamError::Malformed)?;
    let colon = body
        .iter()
        .position(|&b| b == b':')
        .ok_or(ParamError::Malformed)?;
    let (key, rest) = body.split_at(colon);
    let value = rest.get(1..).unwrap_or_default();
    if key.is_empty() || !body.iter().all(|b| (0x20..0x7F).contains(b)) {
        return Err(ParamError::Malformed);
    }
    Ok((
        String::from_utf8_lossy(key).into_owned(),
        String::from_utf8_lossy(value).into_owned(),
    ))
}

/// The sensor's geometry from `PP` (spec §8.12; urg_c `receive_parameter()`
/// requires the same seven keys).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ScipGeometry {
    /// `DMIN`: shortest valid range, mm; smaller values are error codes.
    pub dmin_mm: u32,
    /// `DMAX`: longest valid range, mm.
    pub dmax_mm: u32,
    /// `ARES`: steps in a full revolution.
    pub ares: u32,
    /// `AMIN`: first measurable step.
    pub amin: u32,
    /// `AMAX`: last measurable step.
    pub amax: u32,
    /// `AFRT`: the step pointing forward (+x).
    pub afrt: u32,
    /// `SCAN`: revolutions per minute.
    pub scan_rpm: u32,
}

impl ScipGeometry {
    /// Reads and checks the seven keys. Limits: `ARES` 1..=65536, `SCAN`
    /// 1..=100000, `AMIN <= AMAX <= 9999` (steps are 4-digit command
    /// parameters), `DMIN < DMAX`.
    pub fn from_pairs(pairs: &[(String, String)]) -> Result<Self, ParamError> {
        let geometry = Self {
            dmin_mm: number(pairs, "DMIN")?,
            dmax_mm: number(pairs, "DMAX")?,
            ares: number(pairs, "ARES")?,
            amin: number(pairs, "AMIN")?,
            amax: number(pairs, "AMAX")?,
            afrt: number(pairs, "AFRT")?,
            scan_rpm: number(pairs, "SCAN")?,
        };
        geometry.check()?;
        Ok(geometry)
    }

    fn check(&self) -> Result<(), ParamError> {
        let invalid = |key: &'static str, value: u32| ParamError::Invalid {
            key,
            value: value.to_string(),
        };
        if !(1..=65_536).contains(&self.ares) {
            return Err(invalid("ARES", self.ares));
        }
        if !(1..=100_000).contains(&self.scan_rpm) {
            return Err(invalid("SCAN", self.scan_rpm));
        }
        if self.amax > 9999 || self.amin > self.amax {
            return Err(invalid("AMAX", self.amax));
        }
        if self.dmin_mm >= self.dmax_mm {
            return Err(invalid("DMAX", self.dmax_mm));
        }
        Ok(())
    }

    /// Nanoseconds per revolution: 60e9 / `SCAN`.
    pub fn revolution_ns(&self) -> f64 {
        60e9 / f64::from(self.scan_rpm)
    }

    /// Nanoseconds per step: a revolution over `ARES`.
    pub fn step_ns(&self) -> f64 {
        self.revolution_ns() / f64::from(self.ares)
    }

    /// The angle of `step` in radians, counter-clockwise from forward
    /// (REP-103): `(step - AFRT) * 2π / ARES` (spec §5 "Measurement Direction
    /// and Points": steps increase counter-clockwise seen from above; urg_c
    /// `urg_step2rad()`).
    pub fn angle(&self, step: u32) -> f64 {
        (f64::from(step) - f64::from(self.afrt)) * std::f64::consts::TAU / f64::from(self.ares)
    }
}

fn number(pairs: &[(String, String)], key: &'static str) -> Result<u32, ParamError> {
    let (_, value) = pairs
        .iter()
        .find(|(k, _)| k == key)
        .ok_or(ParamError::Missing(key))?;
    // Read the leading digits after any blanks, as urg_c's strtol() does, so
    // a trailing unit or comment on some model does not reject the reply.
    let digits: String = value
        .trim()
        .chars()
        .take_while(char::is_ascii_digit)
        .collect();
    digits.parse().map_err(|_| ParamError::Invalid {
        key,
        value: value.clone(),
    })
}

/// The `STAT` texts of a working sensor, as urg_node accepts them
/// (ros-drivers/urg_node `src/urg_node.cpp` `populateDiagnosticsStatus()`).
const HEALTHY_STAT: [&str; 3] = [
    "Sensor works well.",
    "Stable 000 no error.",
    "sensor is working normally",
];

/// The health an `II` reply reports: ok when `STAT` is one of the texts of a
/// working sensor; the detail is the `STAT` text.
pub fn health(pairs: &[(String, String)]) -> (bool, String) {
    match pairs.iter().find(|(k, _)| k == "STAT") {
        Some((_, stat)) => {
            let ok = HEALTHY_STAT
                .iter()
                .any(|h| h.eq_ignore_ascii_case(stat.trim()));
            (ok, format!("STAT: {stat}"))
        }
        None => (false, "II reply has no STAT".to_owned()),
    }
}
