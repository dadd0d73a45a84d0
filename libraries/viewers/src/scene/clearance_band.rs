//! How close a link is, in four bands that every viewer colours the same way.

use shroud_msg::{CollisionMessage, LinkClearance};
use std::collections::BTreeMap;

/// Linear RGBA of a link no verdict speaks for (no guard yet, or a link the
/// guard does not report): neutral grey.
pub const NO_VERDICT_RGBA: [f64; 4] = [0.6, 0.6, 0.6, 0.6];

/// Each link's band in the guard's verdict `msg`.
pub fn link_bands(msg: &CollisionMessage) -> BTreeMap<String, ClearanceBand> {
    msg.links
        .iter()
        .map(|l| (l.link.clone(), ClearanceBand::of(l, msg.stop_distance)))
        .collect()
}

/// A link's clearance band against the guard's stop distance.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ClearanceBand {
    /// At or within the stop distance (0 when contact cannot be excluded).
    Stop,
    /// Within twice the stop distance.
    Near,
    Clear,
    /// Its shapes reach space no fresh surrogate covers: nothing is known there.
    Unobserved,
}

impl ClearanceBand {
    /// The band of `link` under a guard with `stop_distance`. Unobserved wins
    /// over a large clearance (nothing vouches for that space) but not over a
    /// stop (a known obstacle is the more urgent fact).
    pub fn of(link: &LinkClearance, stop_distance: f64) -> Self {
        // A NaN clearance belongs in the stop band too.
        if link.clearance.is_nan() || link.clearance <= stop_distance {
            Self::Stop
        } else if link.unobserved {
            Self::Unobserved
        } else if link.clearance <= 2.0 * stop_distance {
            Self::Near
        } else {
            Self::Clear
        }
    }

    /// The name viewers receive (`stop`, `near`, `clear`, `unobserved`).
    pub fn name(self) -> &'static str {
        match self {
            Self::Stop => "stop",
            Self::Near => "near",
            Self::Clear => "clear",
            Self::Unobserved => "unobserved",
        }
    }

    /// Linear RGBA in [0, 1]: red, amber, green, grey-violet.
    pub fn rgba(self) -> [f64; 4] {
        match self {
            Self::Stop => [0.90, 0.12, 0.10, 0.95],
            Self::Near => [0.98, 0.62, 0.05, 0.85],
            Self::Clear => [0.20, 0.75, 0.35, 0.60],
            Self::Unobserved => [0.55, 0.45, 0.80, 0.75],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn link(clearance: f64, unobserved: bool) -> LinkClearance {
        LinkClearance {
            link: "l".into(),
            clearance,
            unobserved,
        }
    }

    #[test]
    fn bands_follow_the_stop_distance() {
        let d = 0.05;
        assert_eq!(ClearanceBand::of(&link(0.0, false), d), ClearanceBand::Stop);
        assert_eq!(
            ClearanceBand::of(&link(0.05, false), d),
            ClearanceBand::Stop
        );
        assert_eq!(
            ClearanceBand::of(&link(0.07, false), d),
            ClearanceBand::Near
        );
        assert_eq!(
            ClearanceBand::of(&link(0.10, false), d),
            ClearanceBand::Near
        );
        assert_eq!(
            ClearanceBand::of(&link(0.11, false), d),
            ClearanceBand::Clear
        );
        assert_eq!(
            ClearanceBand::of(&link(0.3, true), d),
            ClearanceBand::Unobserved
        );
        assert_eq!(ClearanceBand::of(&link(0.01, true), d), ClearanceBand::Stop);
        assert_eq!(
            ClearanceBand::of(&link(f64::NAN, false), d),
            ClearanceBand::Stop
        );
        for band in [
            ClearanceBand::Stop,
            ClearanceBand::Near,
            ClearanceBand::Clear,
            ClearanceBand::Unobserved,
        ] {
            assert!(band.rgba().iter().all(|c| (0.0..=1.0).contains(c)));
        }
    }
}
