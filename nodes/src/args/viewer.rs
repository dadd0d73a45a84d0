//! The options of the viewer nodes (the dashboard, the Foxglove bridge): the
//! clouds' point budget, the pacing rate, the arms drawn, the verdict timeout
//! and the blend node to drive, declared and checked once for both.

use crate::arm_file::read_arm_file;
use anyhow::Result;
use clap::Args;
use shroud_guard::ArmModel;
use std::path::PathBuf;

#[derive(Debug, Clone, Args)]
pub struct ViewerArgs {
    /// Most points of each cloud sent to a viewer, thinned by an even stride
    /// (a dashboard browser may ask for fewer); default 60000 on the
    /// dashboard, 50000 on the Foxglove bridge.
    #[arg(long, visible_alias = "points-budget")]
    pub point_budget: Option<usize>,
    /// Most updates a second of each cloud, surrogate and smooth fit (the
    /// dashboard; arms, verdicts and nodes are not paced) or cloud, surrogate
    /// and arm (the Foxglove bridge; its clients' queues count messages, not
    /// bytes) sent to viewers; the latest waits. What a viewer needs, and what
    /// keeps a 30 Hz 300K-point stream from costing the robot's cores.
    #[arg(long, default_value_t = 10.0)]
    pub max_rate: f64,
    /// An arm file (as the guard's) whose arm is drawn at its joint states. Repeatable.
    #[arg(long = "arm-file", value_name = "FILE")]
    pub arm_files: Vec<PathBuf>,
    /// Seconds without a verdict after which an arm shows `no-verdict` (STOP).
    #[arg(long, default_value_t = 0.5)]
    pub verdict_timeout: f64,
    /// The blend node that the dashboard's palette or a Foxglove client's
    /// `/shroud/blend` drives (its command stream); default: the first that
    /// announces itself in the namespace.
    #[arg(long)]
    pub blend_stream: Option<String>,
}

/// [`ViewerArgs`], checked, with the arm files read.
#[derive(Debug, Clone)]
pub struct ViewerSettings {
    pub point_budget: usize,
    /// Least nanoseconds between two updates of one paced stream.
    pub pace_ns: u64,
    pub arms: Vec<ArmModel>,
    pub verdict_timeout_ns: u64,
    pub blend_stream: Option<String>,
}

impl ViewerArgs {
    /// Checks the options (the point budget is `default_point_budget` unless
    /// given) and reads the arm files.
    pub fn settings(&self, default_point_budget: usize) -> Result<ViewerSettings> {
        let point_budget = self.point_budget.unwrap_or(default_point_budget);
        let view = ViewLimits {
            point_budget: ("--point-budget", point_budget),
            rate: ("--max-rate", self.max_rate, "updates"),
            verdict_timeout: self.verdict_timeout,
            arm_files: &self.arm_files,
        };
        let (pace_ns, arms, verdict_timeout_ns) = view.check()?;
        Ok(ViewerSettings {
            point_budget,
            pace_ns,
            arms,
            verdict_timeout_ns,
            blend_stream: self.blend_stream.clone(),
        })
    }
}

/// What every view of the graph is limited by, as given on a command line
/// (the viewers' and `shroud record --foxglove`'s flags name them apart).
pub struct ViewLimits<'a> {
    /// (flag, points).
    pub point_budget: (&'static str, usize),
    /// (flag, per second, what is paced).
    pub rate: (&'static str, f64, &'static str),
    pub verdict_timeout: f64,
    pub arm_files: &'a [PathBuf],
}

impl ViewLimits<'_> {
    /// Checks the limits and reads the arm files: (least nanoseconds between
    /// two updates of a stream, the arms, the verdict timeout in nanoseconds).
    pub fn check(&self) -> Result<(u64, Vec<ArmModel>, u64)> {
        let (flag, points) = self.point_budget;
        anyhow::ensure!(
            (1000..=2_000_000).contains(&points),
            "{flag} must be 1000 to 2000000 points, not {points}"
        );
        let (flag, rate, what) = self.rate;
        anyhow::ensure!(
            rate.is_finite() && rate > 0.0 && rate <= 1000.0,
            "{flag} must be more than 0 and at most 1000 {what} a second, not {rate}"
        );
        let timeout = self.verdict_timeout;
        anyhow::ensure!(
            timeout.is_finite() && timeout > 0.0 && timeout <= 3600.0,
            "--verdict-timeout must be more than 0 and at most 3600 seconds, not {timeout}"
        );
        let arms = self
            .arm_files
            .iter()
            .map(|path| read_arm_file(path).map(|file| file.arm))
            .collect::<Result<Vec<_>>>()?;
        Ok(((1e9 / rate) as u64, arms, (timeout * 1e9) as u64))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct Line {
        #[command(flatten)]
        viewer: ViewerArgs,
    }

    fn parse(args: &[&str]) -> ViewerArgs {
        Line::try_parse_from(std::iter::once("viewer").chain(args.iter().copied()))
            .unwrap()
            .viewer
    }

    #[test]
    fn defaults_and_both_budget_spellings() {
        let settings = parse(&[]).settings(60_000).unwrap();
        assert_eq!(settings.point_budget, 60_000);
        assert_eq!(settings.pace_ns, 100_000_000);
        assert_eq!(settings.verdict_timeout_ns, 500_000_000);
        assert!(settings.arms.is_empty() && settings.blend_stream.is_none());
        for flag in ["--point-budget", "--points-budget"] {
            let settings = parse(&[flag, "2000"]).settings(50_000).unwrap();
            assert_eq!(settings.point_budget, 2000);
        }
    }

    #[test]
    fn out_of_range_values_name_their_option() {
        for (args, needle) in [
            (&["--point-budget", "999"][..], "--point-budget"),
            (&["--max-rate", "0"], "--max-rate"),
            (&["--max-rate", "NaN"], "--max-rate"),
            (&["--verdict-timeout", "3601"], "--verdict-timeout"),
            (&["--arm-file", "/no/such/arm.toml"], "/no/such/arm.toml"),
        ] {
            let err = parse(args).settings(50_000).unwrap_err();
            assert!(format!("{err:#}").contains(needle), "{args:?}: {err:#}");
        }
    }
}
