//! `shroud-bench guard-soundness`: the brute-force soundness run of the
//! collision guard (`shroud_sim::soundness`) over `--cases` random scenes,
//! printed as a markdown table with the optimistic findings, if any, one
//! simplest example per class. Fails (non-zero exit) when a `clear` verdict
//! was optimistic, so that it can gate a release.

use super::BenchArgs;
use anyhow::{bail, Result};
use shroud_sim::soundness::{minimise, run, FindingClass, SoundnessParams, SoundnessReport};
use std::time::Instant;

pub fn run_bench(args: &BenchArgs) -> Result<()> {
    let params = SoundnessParams {
        verdicts_per_case: args.verdicts_per_case,
        max_obstacle_speed: args.obstacle_speed,
        sandwich_share: args.sandwich_share,
        black_share: args.black_share,
        parallel_rays: args.parallel_rays,
        state_field_of_view: !args.no_field_of_view,
        state_no_return: !args.no_empty_rays,
        sectors: args.sectors,
        sector_reach: args.sector_reach,
        ..SoundnessParams::default()
    };
    let start = Instant::now();
    let report = run(&params, args.cases, args.seed)?;
    let wall = start.elapsed().as_secs_f64();
    print!("{}", table(&report, &params, args, wall));
    if report.optimistic > 0 || report.contacts > 0 {
        println!("\n## Optimistic verdicts by class\n");
        for (class, n) in FindingClass::ALL.iter().zip(report.classes) {
            println!("- {}: {n}", class.name());
        }
        println!("\n## The simplest kept example of each class\n");
        for finding in report.simplest_findings() {
            println!("```\n{finding}```\n");
            // Only the solids and sensors it needs: the same pose and time.
            match minimise(&params, finding)? {
                Some(scene) => {
                    println!("Minimised (same pose and decision time):\n\n```\n{scene}```\n")
                }
                None => println!("(it does not replay alone)\n"),
            }
        }
        bail!(
            "{} optimistic verdicts ({} contacts)",
            report.optimistic,
            report.contacts
        );
    }
    Ok(())
}

fn table(r: &SoundnessReport, p: &SoundnessParams, args: &BenchArgs, wall: f64) -> String {
    let v = &r.verdicts;
    let total = v.total();
    let share = |n: u64| {
        if total == 0 {
            0.0
        } else {
            100.0 * n as f64 / total as f64
        }
    };
    let conservativeness = r
        .conservativeness()
        .map_or("n/a (nothing eligible)".into(), |c| {
            format!(
                "{:.1} % ({} of {} eligible verdicts, {} of them unobserved; target <= 33.3 %)",
                100.0 * c,
                r.eligible_stopped,
                r.eligible,
                r.eligible_unobserved
            )
        });
    let rows: Vec<(String, String)> = vec![
        ("scenes".into(), r.scenes.to_string()),
        (
            "views fitted / without a view".into(),
            format!("{} / {}", r.views, r.views_missing),
        ),
        ("points scanned".into(), r.points.to_string()),
        ("verdicts".into(), total.to_string()),
        ("clear".into(), format!("{} ({:.1} %)", v.clear, share(v.clear))),
        ("stop".into(), format!("{} ({:.1} %)", v.stop, share(v.stop))),
        (
            "unobserved".into(),
            format!("{} ({:.1} %)", v.unobserved, share(v.unobserved)),
        ),
        ("stale".into(), format!("{} ({:.1} %)", v.stale, share(v.stale))),
        (
            "no surrogate".into(),
            format!("{} ({:.1} %)", v.no_surrogate, share(v.no_surrogate)),
        ),
        ("**optimistic verdicts**".into(), format!("**{}**", r.optimistic)),
        ("**contacts**".into(), format!("**{}**", r.contacts)),
        ("conservativeness".into(), conservativeness),
        (
            "conservativeness beyond the motion allowance".into(),
            r.conservativeness_beyond_allowance()
                .map_or("n/a".into(), |c| {
                    format!(
                        "{:.1} % (leaving out {} eligible verdicts, {} of them stopped, whose true distance \
                         is within the stop distance plus the freshest view's motion allowance)",
                        100.0 * c,
                        r.eligible_forced,
                        r.eligible_forced_stopped
                    )
                }),
        ),
        (
            "closest clear (true distance)".into(),
            format!("{:.4} m", r.closest_clear),
        ),
        (
            "largest sampling margin".into(),
            format!("{:.4} m", r.max_sampling_margin),
        ),
        (
            "parameters".into(),
            format!(
                "--cases {} --seed {} --verdicts-per-case {}; stop distance {} m, obstacle speed <= {} m/s, \
                 horizon {} s, max age {} s, {} decision times per pose, <= {} rays per sensor, \
                 sandwich share {}, black share {}, {} rays, field of view {}, empty rays {}, {}",
                args.cases,
                args.seed,
                p.verdicts_per_case,
                p.stop_distance,
                p.max_obstacle_speed,
                p.horizon,
                p.max_age,
                p.timings_per_pose,
                p.max_rays,
                p.sandwich_share,
                p.black_share,
                if p.parallel_rays { "parallel" } else { "perspective" },
                match (p.parallel_rays, p.state_field_of_view) {
                    (true, _) => "not stated (parallel rays)",
                    (false, true) => "stated",
                    (false, false) => "not stated",
                },
                match (p.parallel_rays, p.state_no_return) {
                    (true, _) => "not stated (parallel rays)",
                    (false, true) => "stated",
                    (false, false) => "not stated",
                },
                match p.sectors {
                    0 => "whole views only".to_string(),
                    n => format!("{n} x {n} sectors per view (reach {})", p.sector_reach),
                }
            ),
        ),
        (
            "wall time".into(),
            format!(
                "{wall:.1} s ({:.0} verdicts/s, {:.1} scenes/s, {} threads)",
                total as f64 / wall.max(1e-9),
                r.scenes as f64 / wall.max(1e-9),
                rayon::current_num_threads()
            ),
        ),
    ];
    let mut out = String::from("| guard soundness | |\n| --- | --- |\n");
    for (name, value) in rows {
        out.push_str(&format!("| {name} | {value} |\n"));
    }
    out
}
