//! RadarState (0x201, every 50 ms) and VersionID (0x700) read as the radar's
//! health, its configuration as it reports it, and its identity.

use super::layout::{code, radar_state as rs};

/// The error bits of RadarState, in the DBC's order, with the names health
/// reports them by.
pub const ERROR_NAMES: [&str; 5] = [
    "persistent error",
    "interference",
    "temperature error",
    "temporary error",
    "voltage error",
];

/// One RadarState, decoded.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct RadarState {
    pub errors: [bool; 5],
    pub max_distance_m: f64,
    pub radar_power: u32,
    pub sensor_id: u32,
    pub sort_index: u32,
    pub output_type: u32,
    pub send_quality: bool,
    pub send_ext_info: bool,
    pub motion_rx_state: u32,
    pub rcs_threshold: u32,
}

impl RadarState {
    /// From the values bound by `layout::radar_state::NAMES`; `None` when a
    /// code is not a whole number (a user's DBC with odd scaling).
    pub fn from_values(v: &[f64; 14]) -> Option<Self> {
        let mut errors = [false; 5];
        for (bit, value) in errors.iter_mut().zip(v.iter().take(rs::ERRORS)) {
            *bit = code(*value)? != 0;
        }
        let max_distance_m = v[rs::MAX_DISTANCE];
        if !max_distance_m.is_finite() {
            return None;
        }
        Some(Self {
            errors,
            max_distance_m,
            radar_power: code(v[rs::RADAR_POWER])?,
            sensor_id: code(v[rs::SENSOR_ID])?,
            sort_index: code(v[rs::SORT_INDEX])?,
            output_type: code(v[rs::OUTPUT_TYPE])?,
            send_quality: code(v[rs::SEND_QUALITY])? != 0,
            send_ext_info: code(v[rs::SEND_EXT_INFO])? != 0,
            motion_rx_state: code(v[rs::MOTION_RX])?,
            rcs_threshold: code(v[rs::RCS_THRESHOLD])?,
        })
    }

    /// The names of the error bits that are set.
    pub fn error_names(&self) -> Vec<&'static str> {
        ERROR_NAMES
            .iter()
            .zip(self.errors)
            .filter_map(|(name, set)| set.then_some(*name))
            .collect()
    }

    /// The configuration the radar reports, as identity pairs.
    pub fn identity(&self) -> Vec<(String, String)> {
        let pairs = [
            ("output_type", output_type_name(self.output_type).to_owned()),
            ("max_distance_m", format!("{}", self.max_distance_m)),
            ("send_quality", self.send_quality.to_string()),
            ("send_ext_info", self.send_ext_info.to_string()),
            ("sensor_id", self.sensor_id.to_string()),
            ("radar_power", self.radar_power.to_string()),
            ("sort_index", self.sort_index.to_string()),
            ("motion_rx_state", self.motion_rx_state.to_string()),
            ("rcs_threshold", self.rcs_threshold.to_string()),
        ];
        pairs.into_iter().map(|(k, v)| (k.to_owned(), v)).collect()
    }
}

/// `OutputTypeCfg`: 0 none, 1 objects, 2 clusters (sensors.md §2.2).
pub(super) fn output_type_name(code: u32) -> &'static str {
    match code {
        0 => "none",
        1 => "objects",
        2 => "clusters",
        _ => "unknown",
    }
}

/// VersionID as identity pairs: `firmware` = major.minor.patch,
/// `extended_range`, `country_code`; `None` when a value is not a code.
pub(super) fn version_identity(v: &[f64; 5]) -> Option<Vec<(String, String)>> {
    let [major, minor, patch, extended, country] = v.map(code);
    Some(vec![
        (
            "firmware".to_owned(),
            format!("{}.{}.{}", major?, minor?, patch?),
        ),
        ("extended_range".to_owned(), (extended? != 0).to_string()),
        ("country_code".to_owned(), country?.to_string()),
    ])
}
