//! How fast an arm may move, as every viewer shows it: the speed scale of
//! the verdict a display vouches for (speed and separation monitoring,
//! docs/guard-separation-monitoring.md), with the link whose separation
//! limits it. Only a fresh `clear` lets the arm move; every other verdict,
//! and a guard fallen silent, shows the arm stopped.

use shroud_guard::ShownVerdict;
use shroud_msg::GuardVerdict;

/// What the scale lets the arm do.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SpeedState {
    /// A `clear` at scale 1: each joint up to its velocity limit.
    Full,
    /// A `clear` below scale 1.
    Scaled,
    /// Anything but a fresh `clear`: the arm may not move.
    Stopped,
}

impl SpeedState {
    /// The name viewers receive (`full`, `scaled`, `stopped`).
    pub fn name(self) -> &'static str {
        match self {
            Self::Full => "full",
            Self::Scaled => "scaled",
            Self::Stopped => "stopped",
        }
    }
}

/// An arm's speed as the verdict shown for it allows.
#[derive(Debug, Clone, PartialEq)]
pub struct ArmSpeed {
    /// The verdict shown (the guard's, or `no-verdict` for a silent guard).
    pub verdict: GuardVerdict,
    pub state: SpeedState,
    /// In [0, 1]: the guard's `speed_scale` for a fresh `clear`, 0 for
    /// every other verdict shown.
    pub scale: f64,
    /// The link the guard's verdict names as limiting the scale; `None`
    /// when it names none, or when the verdict shown is not the guard's
    /// (`no-verdict`).
    pub limiting_link: Option<String>,
    /// Metres: the verdict's protective separation distance `S_p` (that of
    /// the limiting link at the scale; the stop distance when nothing
    /// limits it); `None` when the verdict shown is not the guard's.
    pub protective_distance: Option<f64>,
}

impl ArmSpeed {
    /// The speed `shown` allows. A silent guard's last message says nothing
    /// any more: `no-verdict` takes none of its numbers.
    pub fn of(shown: &ShownVerdict<'_>) -> Self {
        let guard = shown
            .message
            .filter(|_| shown.verdict != GuardVerdict::NoVerdict);
        let scale = match guard {
            // A NaN or out-of-range scale is never a reason to show motion
            // (decoded messages have neither).
            Some(msg) if shown.verdict == GuardVerdict::Clear && msg.speed_scale > 0.0 => {
                msg.speed_scale.min(1.0)
            }
            _ => 0.0,
        };
        let state = if scale <= 0.0 {
            SpeedState::Stopped
        } else if scale >= 1.0 {
            SpeedState::Full
        } else {
            SpeedState::Scaled
        };
        Self {
            verdict: shown.verdict,
            state,
            scale,
            limiting_link: guard
                .map(|m| m.limiting_link.clone())
                .filter(|l| !l.is_empty()),
            protective_distance: guard
                .map(|m| m.protective_distance)
                .filter(|d| d.is_finite()),
        }
    }

    /// The scale in whole percent, rounded down (0.29 is 29 %, not the
    /// 28.999... of `100 * 0.29`) so that a slowed arm never reads 100 %:
    /// `"62 %"`, and `"<1 %"` for a moving arm below 1 %.
    pub fn percent(&self) -> String {
        if self.scale > 0.0 && self.scale < 0.01 {
            return "<1 %".into();
        }
        let most = if self.scale < 1.0 { 99.0 } else { 100.0 };
        format!("{} %", (100.0 * self.scale + 1e-9).floor().min(most))
    }

    /// One line for a label: `full speed`; `62 % speed, limited by forearm
    /// (S_p 0.840 m)` (or `rise-limited (speeding up)` when the verdict names
    /// no link: the guard's rise limit alone holds the scale); `stopped
    /// (stop)` with the verdict shown.
    pub fn label(&self) -> String {
        match self.state {
            SpeedState::Full => "full speed".into(),
            SpeedState::Scaled => {
                let why = match (&self.limiting_link, self.protective_distance) {
                    (Some(link), Some(sp)) => format!("limited by {link} (S_p {sp:.3} m)"),
                    (Some(link), None) => format!("limited by {link}"),
                    (None, _) => "rise-limited (speeding up)".into(),
                };
                format!("{} speed, {why}", self.percent())
            }
            SpeedState::Stopped => format!("stopped ({})", self.verdict.name()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use shroud_guard::VerdictWatch;
    use shroud_msg::sample_collision;

    fn scaled(scale: f64, link: &str, sp: f64) -> shroud_msg::CollisionMessage {
        let mut msg = sample_collision(GuardVerdict::Clear);
        (msg.speed_scale, msg.limiting_link, msg.protective_distance) = (scale, link.into(), sp);
        msg
    }

    #[test]
    fn a_scaled_clear_names_its_limiting_link_and_protective_distance() {
        let mut watch = VerdictWatch::new(1_000);
        watch.on_verdict(scaled(0.625, "forearm", 0.84), 0);
        let speed = ArmSpeed::of(&watch.shown(10));
        assert_eq!((speed.state, speed.scale), (SpeedState::Scaled, 0.625));
        assert_eq!(speed.limiting_link.as_deref(), Some("forearm"));
        assert_eq!(speed.protective_distance, Some(0.84));
        assert_eq!(
            speed.label(),
            "62 % speed, limited by forearm (S_p 0.840 m)"
        );
        watch.on_verdict(scaled(0.999, "", 0.05), 0);
        let speed = ArmSpeed::of(&watch.shown(10));
        assert_eq!(speed.label(), "99 % speed, rise-limited (speeding up)");
        let percent = |scale: f64| {
            let mut watch = VerdictWatch::new(1_000);
            watch.on_verdict(scaled(scale, "tool", 0.2), 0);
            ArmSpeed::of(&watch.shown(10)).percent()
        };
        let shown: Vec<String> = [0.004, 0.29, 0.5, 1.0 - 1e-12, 1.0]
            .into_iter()
            .map(percent)
            .collect();
        assert_eq!(shown, ["<1 %", "29 %", "50 %", "99 %", "100 %"]);
        watch.on_verdict(scaled(1.0, "", 0.05), 0);
        let speed = ArmSpeed::of(&watch.shown(10));
        assert_eq!(
            (speed.state, speed.label().as_str()),
            (SpeedState::Full, "full speed")
        );
        assert_eq!(speed.limiting_link, None);
    }

    #[test]
    fn a_stop_or_a_silent_guard_is_stopped_and_silence_keeps_no_numbers() {
        let mut watch = VerdictWatch::new(1_000);
        let none = ArmSpeed::of(&watch.shown(0));
        assert_eq!((none.state, none.scale), (SpeedState::Stopped, 0.0));
        assert_eq!(none.label(), "stopped (no-verdict)");
        assert_eq!((none.limiting_link, none.protective_distance), (None, None));
        let mut stop = sample_collision(GuardVerdict::Stop);
        (stop.limiting_link, stop.protective_distance) = ("tool".into(), 0.14);
        watch.on_verdict(stop, 0);
        let speed = ArmSpeed::of(&watch.shown(10));
        assert_eq!((speed.state, speed.scale), (SpeedState::Stopped, 0.0));
        assert_eq!(speed.label(), "stopped (stop)");
        assert_eq!(speed.limiting_link.as_deref(), Some("tool"));
        // A scaled clear that has gone stale is a stop, without its numbers.
        watch.on_verdict(scaled(0.5, "forearm", 0.84), 0);
        let silent = ArmSpeed::of(&watch.shown(5_000));
        assert_eq!(silent.verdict, GuardVerdict::NoVerdict);
        assert_eq!((silent.state, silent.scale), (SpeedState::Stopped, 0.0));
        assert_eq!(
            (silent.limiting_link, silent.protective_distance),
            (None, None)
        );
    }
}
