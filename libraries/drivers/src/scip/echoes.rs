//! Multi-echo scan data (`ND`/`NE`/`HD`/`HE`): a step's first echo is a plain
//! value group, each further echo of the same step is `&` and a value group
//! (ranges, or range and intensity for `NE`/`HE`). The `&` is a character of
//! the data stream like any other, so it and its value may straddle a
//! 64-character line (urg_c `current/src/urg_sensor.c`
//! `receive_length_data()`: a group starting with `&` is "multi-echo data" of
//! the previous step; at most `URG_MAX_ECHO` = 3 echoes per step).

use super::command::MAX_ECHOES;
use super::scan_error::ScanDataError;

/// The character that starts every echo after a step's first.
pub const ECHO_MARK: u8 = b'&';

/// A multi-echo scan's data cut into value groups.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) struct EchoSplit {
    /// The value groups without their `&`s, concatenated in wire order.
    pub groups: Vec<u8>,
    /// Echoes per step, each 1..=[`MAX_ECHOES`], in step order.
    pub echo_counts: Vec<u8>,
}

/// Cuts `text` (the data lines joined, sums stripped) into `steps` steps of
/// `group`-character echoes. Rejected: a `&` before the first value, a fourth
/// echo, a `&` without a whole value after it, more or fewer steps than
/// requested.
pub(super) fn split_echoes(
    text: &[u8],
    group: usize,
    steps: usize,
) -> Result<EchoSplit, ScanDataError> {
    let mut split = EchoSplit {
        groups: Vec::with_capacity(text.len()),
        echo_counts: Vec::with_capacity(steps),
    };
    let mut rest = text;
    while let Some((&first, after)) = rest.split_first() {
        rest = if first == ECHO_MARK {
            split.add_echo(after, group)?
        } else {
            split.add_step(rest, group, steps)?
        };
    }
    if split.echo_counts.len() < steps {
        return Err(split.missing_steps(steps));
    }
    Ok(split)
}

impl EchoSplit {
    /// Another echo of the last step: `text` follows its `&`.
    fn add_echo<'a>(&mut self, text: &'a [u8], group: usize) -> Result<&'a [u8], ScanDataError> {
        let count = self
            .echo_counts
            .last_mut()
            .ok_or(ScanDataError::EchoBeforeFirstValue)?;
        if usize::from(*count) >= MAX_ECHOES {
            return Err(ScanDataError::TooManyEchoes);
        }
        *count += 1;
        let value = text
            .get(..group)
            .filter(|value| !value.contains(&ECHO_MARK))
            .ok_or(ScanDataError::DanglingEchoMark)?;
        self.groups.extend_from_slice(value);
        Ok(text.get(group..).unwrap_or_default())
    }

    /// The first echo of the next step.
    fn add_step<'a>(
        &mut self,
        text: &'a [u8],
        group: usize,
        steps: usize,
    ) -> Result<&'a [u8], ScanDataError> {
        if self.echo_counts.len() >= steps {
            return Err(ScanDataError::ExtraData { expected: steps });
        }
        let value = text.get(..group).ok_or_else(|| self.missing_steps(steps))?;
        self.echo_counts.push(1);
        self.groups.extend_from_slice(value);
        Ok(text.get(group..).unwrap_or_default())
    }

    fn missing_steps(&self, steps: usize) -> ScanDataError {
        ScanDataError::MissingSteps {
            expected: steps,
            got: self.echo_counts.len(),
        }
    }
}
