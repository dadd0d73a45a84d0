//! `shroud-bench guard-separation`: the brute-force check of the guard's
//! speed and separation monitoring (`shroud_sim::soundness::separation`)
//! over `--trajectories` closed-loop simulations, printed as a markdown
//! table with the productivity of the scaled guard against a binary stop at
//! the same safety. Fails (non-zero exit) when the moving arm ever came
//! nearer to anything than the stop distance less the sampling margin, and
//! prints the first such failure with its trajectory, which
//! `--replay SEED` runs alone.

use super::BenchArgs;
use anyhow::{bail, Context, Result};
use clap::ValueEnum;
use shroud_sim::soundness::separation::{
    run, run_trajectory, ArmBehaviour, SeparationArms, SeparationParams, SeparationReport,
    SeparationScene,
};
use std::time::Instant;

/// How the simulated arm treats its verdicts (`--arm`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ArmChoice {
    /// The contract and no better.
    Obeys,
    /// Negative control: full speed whenever the deadman allows motion.
    IgnoresScale,
    /// Negative control: obeys `--arm-amount` seconds later than declared.
    Late,
    /// Negative control: stops take `--arm-amount` times the declared distance and time.
    SoftBrakes,
}

/// The obstacle speed the suite uses unless `--obstacle-speed` is given: a
/// person walking (ISO 13855).
const DEFAULT_OBSTACLE_SPEED: f64 = 1.6;

fn params(args: &BenchArgs) -> SeparationParams {
    let defaults = SeparationParams::default();
    SeparationParams {
        obstacle_speed: if args.obstacle_speed_given {
            args.obstacle_speed
        } else {
            DEFAULT_OBSTACLE_SPEED
        },
        duration: args.duration,
        max_rays: args.max_rays.unwrap_or(defaults.max_rays),
        parallel_rays: !args.perspective,
        sandwich_share: if args.sandwich_share_given {
            args.sandwich_share
        } else {
            defaults.sandwich_share
        },
        behaviour: match args.arm {
            ArmChoice::Obeys => ArmBehaviour::Obeys,
            ArmChoice::IgnoresScale => ArmBehaviour::IgnoresScale,
            ArmChoice::Late => ArmBehaviour::Late(args.arm_amount),
            ArmChoice::SoftBrakes => ArmBehaviour::SoftBrakes(args.arm_amount),
        },
        compare_binary: !args.no_binary,
        person_share: args.person_share,
        mount_lift: args.mount_lift,
        min_height: args.min_height,
        declared_obstacle_speed: args.declared_obstacle_speed,
        velocities_share: args.velocities_share,
        ..defaults
    }
}

/// The command line that reproduces this run.
fn command(args: &BenchArgs, p: &SeparationParams) -> String {
    let mut c = format!(
        "shroud-bench guard-separation --trajectories {} --seed {} --obstacle-speed {} --duration {} --max-rays {}",
        args.trajectories, args.seed, p.obstacle_speed, p.duration, p.max_rays
    );
    if p.person_share != SeparationParams::default().person_share {
        c.push_str(&format!(" --person-share {}", p.person_share));
    }
    if p.velocities_share != SeparationParams::default().velocities_share {
        c.push_str(&format!(" --velocities-share {}", p.velocities_share));
    }
    let d = SeparationParams::default();
    if p.mount_lift != d.mount_lift || p.min_height != d.min_height {
        c.push_str(&format!(
            " --mount-lift {} --min-height {}",
            p.mount_lift, p.min_height
        ));
    }
    if let Some(v) = p.declared_obstacle_speed {
        c.push_str(&format!(" --declared-obstacle-speed {v}"));
    }
    if args.perspective {
        c.push_str(" --perspective");
    }
    if args.no_binary {
        c.push_str(" --no-binary");
    }
    if args.arm != ArmChoice::Obeys {
        let name = args
            .arm
            .to_possible_value()
            .map_or(String::new(), |v| v.get_name().to_owned());
        c.push_str(&format!(" --arm {name}"));
        if matches!(args.arm, ArmChoice::Late | ArmChoice::SoftBrakes) {
            c.push_str(&format!(" --arm-amount {}", args.arm_amount));
        }
    }
    c
}

fn parse_seed(text: &str) -> Result<u64> {
    let parsed = match text.strip_prefix("0x") {
        Some(hex) => u64::from_str_radix(hex, 16),
        None => text.parse(),
    };
    parsed.with_context(|| format!("--replay {text}: not a seed (decimal or 0x hex)"))
}

pub fn run_bench(args: &BenchArgs) -> Result<()> {
    let params = params(args);
    params.validate()?;
    if let Some(text) = &args.replay {
        return replay(&params, parse_seed(text)?);
    }
    let start = Instant::now();
    let report = run(&params, args.trajectories, args.seed)?;
    let wall = start.elapsed().as_secs_f64();
    let extra = vec![
        (
            "command".to_string(),
            format!("`{}`", command(args, &params)),
        ),
        (
            "wall time".to_string(),
            format!(
                "{wall:.1} s ({:.1} trajectories/s, {:.0} decisions/s, {} threads)",
                report.trajectories as f64 / wall.max(1e-9),
                report.decisions() as f64 / wall.max(1e-9),
                rayon::current_num_threads()
            ),
        ),
    ];
    print!("{}", report.table(&params, &extra));
    fail_on(&params, &report, true)
}

/// Prints the first failure and the trajectory it happened in (replayable
/// alone; `with_scene`: its scene too), and fails.
fn fail_on(params: &SeparationParams, report: &SeparationReport, with_scene: bool) -> Result<()> {
    let Some(first) = &report.first_failure else {
        return Ok(());
    };
    println!(
        "\n## The first failure\n\n{first}\n\nReplay it alone with `--replay {:#x}` (and the same parameters).",
        first.seed
    );
    if with_scene {
        let arms = SeparationArms::load(params.mount_lift)?;
        let scene = SeparationScene::draw(&arms, params, first.seed);
        println!("\n```\n{scene}\n```");
    }
    bail!(
        "{} failures of the scaled guard and {} of the binary one, in {} trajectories",
        report.failures,
        report.binary_failures,
        report.failing_trajectories
    )
}

fn replay(params: &SeparationParams, seed: u64) -> Result<()> {
    let arms = SeparationArms::load(params.mount_lift)?;
    let scene = SeparationScene::draw(&arms, params, seed);
    println!("```\n{scene}\n```\n");
    let report = run_trajectory(&arms, params, seed, 0)?;
    print!("{}", report.table(params, &[]));
    fail_on(params, &report, false)
}
