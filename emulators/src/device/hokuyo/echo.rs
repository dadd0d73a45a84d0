//! Multi-echo scans (HD/ND/HE/NE, UTM-30LX): the further echoes of a step
//! behind a partly transparent first surface, and their encoding.
//!
//! Wire format (urg_c `current/src/urg_sensor.c`, `receive_length_data()`):
//! a step's first echo is encoded as in MD/ME; each further echo of the same
//! step follows as `&` and its value (HE/NE: value then intensity), at most
//! `URG_MAX_ECHO` = 3 echoes per step (`urg_sensor.h`). The `&` is one more
//! character of the data stream cut into 64-character lines, so it may end
//! one line while its value starts the next.

use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

use super::command::DataEncoding;
use super::model::ModelSpec;
use super::scan::{encode_value, Measurement};

/// Most echoes of one step (urg_c `URG_MAX_ECHO`).
pub(crate) const MAX_ECHOES: usize = 3;

/// The character that starts a further echo of the same step.
pub(crate) const FURTHER_ECHO_MARK: u8 = b'&';

/// How far behind an echo the next one lies (mm).
const GAP_MM: std::ops::RangeInclusive<u32> = 300..=2000;

/// A further echo's intensity as a fraction of the echo before it: the
/// light that passed the first surface, reflected back through it.
const FURTHER_INTENSITY_SHARE: std::ops::Range<f64> = 0.2..0.8;

/// Mixed into the seed so the echo stream is independent of the range noise
/// (an MD scan and the first echoes of an ND scan read the same).
const SEED_SALT: u64 = 0x6563_686f_6573; // "echoes"

/// The echoes of one output value, nearest first.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct StepEchoes {
    echoes: [Measurement; MAX_ECHOES],
    count: usize,
}

impl StepEchoes {
    fn single(first: Measurement) -> Self {
        StepEchoes {
            echoes: [first; MAX_ECHOES],
            count: 1,
        }
    }

    /// Adds a further echo; returns false when the step already has
    /// [`MAX_ECHOES`].
    fn push(&mut self, echo: Measurement) -> bool {
        let Some(slot) = self.echoes.get_mut(self.count) else {
            return false;
        };
        *slot = echo;
        self.count += 1;
        true
    }

    fn last(&self) -> Measurement {
        let index = self.count.saturating_sub(1);
        self.echoes.get(index).copied().unwrap_or(self.echoes[0])
    }

    /// The echoes, nearest first.
    pub(crate) fn iter(&self) -> impl Iterator<Item = &Measurement> {
        self.echoes.iter().take(self.count)
    }
}

/// Draws the further echoes of multi-echo scans.
pub(crate) struct EchoSampler {
    rng: Pcg64,
    further_probability: f64,
}

impl EchoSampler {
    /// `further_probability`: the chance an echo is followed by another
    /// (non-finite counts as 0; clamped to 0..=1).
    pub(crate) fn new(seed: u64, further_probability: f64) -> Self {
        let probability = if further_probability.is_finite() {
            further_probability.clamp(0.0, 1.0)
        } else {
            0.0
        };
        EchoSampler {
            rng: Pcg64::seed_from_u64(seed ^ SEED_SALT),
            further_probability: probability,
        }
    }

    /// Fills `out` with the echoes of each first echo in `firsts`. A
    /// cluster's further echoes are those of the step it reports.
    pub(crate) fn add_echoes(
        &mut self,
        spec: &ModelSpec,
        firsts: &[Measurement],
        out: &mut Vec<StepEchoes>,
    ) {
        out.clear();
        out.extend(firsts.iter().map(|&first| self.echoes_of(spec, first)));
    }

    /// An error code (below DMIN) has no further echo; a valid echo is
    /// followed by another with `further_probability`, up to
    /// [`MAX_ECHOES`], each [`GAP_MM`] behind the previous and within DMAX.
    fn echoes_of(&mut self, spec: &ModelSpec, first: Measurement) -> StepEchoes {
        let mut step = StepEchoes::single(first);
        if first.range_mm < spec.dmin {
            return step;
        }
        while self.further_probability > 0.0 && self.rng.random::<f64>() < self.further_probability
        {
            let Some(next) = self.behind(spec, step.last()) else {
                break;
            };
            if !step.push(next) {
                break;
            }
        }
        step
    }

    fn behind(&mut self, spec: &ModelSpec, echo: Measurement) -> Option<Measurement> {
        let gap = self.rng.random_range(GAP_MM);
        let range_mm = echo.range_mm.checked_add(gap).filter(|&r| r <= spec.dmax)?;
        let share = self.rng.random_range(FURTHER_INTENSITY_SHARE);
        // `share` < 1, so the product stays below the u32 intensity.
        let intensity = (f64::from(echo.intensity) * share).round() as u32;
        Some(Measurement {
            range_mm,
            intensity,
        })
    }
}

/// Appends the encoded echoes of every step (before cutting into
/// 64-character lines): the first echo, then `&` + value per further echo.
pub(crate) fn encode_echoes(steps: &[StepEchoes], encoding: DataEncoding, out: &mut Vec<u8>) {
    for step in steps {
        for (index, echo) in step.iter().enumerate() {
            if index > 0 {
                out.push(FURTHER_ECHO_MARK);
            }
            encode_value(echo, encoding, out);
        }
    }
}

/// The longest payload `values` multi-echo values of `width` characters
/// each can take.
pub(crate) fn max_payload_len(values: usize, width: usize) -> usize {
    let per_step = MAX_ECHOES * width + (MAX_ECHOES - 1);
    values.saturating_mul(per_step)
}
