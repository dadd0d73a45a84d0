//! Why a mount, motion or cloud window setting was refused.

use thiserror::Error;

/// A setting of the scan-to-cloud assembly that cannot be used.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum AssemblyError {
    #[error("invalid {what} {text:?}: {reason}")]
    Parse {
        what: &'static str,
        text: String,
        reason: String,
    },
    #[error("{0}")]
    Invalid(String),
}

impl AssemblyError {
    pub(super) fn parse(what: &'static str, text: &str, reason: impl Into<String>) -> Self {
        Self::Parse {
            what,
            text: text.to_owned(),
            reason: reason.into(),
        }
    }
}

/// Parses comma-separated finite numbers, exactly `n` of them.
pub(super) fn parse_numbers(
    what: &'static str,
    text: &str,
    n: usize,
) -> Result<Vec<f64>, AssemblyError> {
    let values = text
        .split(',')
        .map(|s| s.trim().parse::<f64>())
        .collect::<Result<Vec<f64>, _>>()
        .map_err(|e| AssemblyError::parse(what, text, e.to_string()))?;
    if values.len() != n {
        return Err(AssemblyError::parse(
            what,
            text,
            format!("expected {n} comma-separated numbers, got {}", values.len()),
        ));
    }
    if let Some(bad) = values.iter().find(|v| !v.is_finite()) {
        return Err(AssemblyError::parse(
            what,
            text,
            format!("{bad} is not finite"),
        ));
    }
    Ok(values)
}
