//! The `key = value` pairs the driver reports as the device's identity once
//! it streams (`DriverOutput::Identity`).

use super::config::BenewakeConfig;
use super::reply::FirmwareVersion;

/// Identity pairs: `model`, `firmware` (`V3.V2.V1` from the version reply, or
/// `unknown`), `frame_rate_hz` (see [`frame_rate_text`]), `unit` (`cm`/`mm`),
/// `max_range_m` and `baud`.
pub fn identity(
    config: &BenewakeConfig,
    firmware: Option<FirmwareVersion>,
    confirmed_rate: Option<u16>,
) -> Vec<(String, String)> {
    let model = config.model;
    let firmware = firmware.map_or_else(|| "unknown".to_string(), |v| v.to_string());
    let max_range_m = f32::from(model.max_range_cm()) / 100.0;
    [
        ("model", model.name().to_string()),
        ("firmware", firmware),
        ("frame_rate_hz", frame_rate_text(config, confirmed_rate)),
        ("unit", config.effective_unit().symbol().to_string()),
        ("max_range_m", max_range_m.to_string()),
        ("baud", config.baud.to_string()),
    ]
    .into_iter()
    .map(|(key, value)| (key.to_string(), value))
    .collect()
}

/// The rate the device echoed (`0 (trigger mode)` for 0); the configured one
/// marked `(unconfirmed)` when no echo came; `device setting` when the driver
/// left the rate alone (no rate configured, or the original TFmini).
pub fn frame_rate_text(config: &BenewakeConfig, confirmed_rate: Option<u16>) -> String {
    let configured = config.frame_rate.filter(|_| config.model.has_commands());
    match (confirmed_rate, configured) {
        (Some(0), _) => "0 (trigger mode)".to_string(),
        (Some(hz), _) => hz.to_string(),
        (None, Some(hz)) => format!("{hz} (unconfirmed)"),
        (None, None) => "device setting".to_string(),
    }
}
