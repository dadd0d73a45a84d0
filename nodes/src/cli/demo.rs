//! `shroud demo`: the simulator's moving spheres streamed into a warm-started
//! sandwich fitter, with a live one-line summary per second.

use crate::timing::median;
use anyhow::Result;
use clap::Args;
use shroud_sim::MovingSpheres;
use shroud_surrogate::{FitOptions, Sides, Surrogate, SurrogateFitter};
use std::time::{Duration, Instant};

#[derive(Debug, Args)]
pub struct DemoArgs {
    /// Points per frame.
    #[arg(long, default_value_t = 100_000)]
    pub points: usize,
    /// Frames per second the simulated scanner produces.
    #[arg(long, default_value_t = 30.0)]
    pub rate: f64,
    /// How long to run (seconds).
    #[arg(long, default_value_t = 10.0)]
    pub seconds: f64,
    #[arg(long, default_value = "20x20")]
    pub grid: String,
}

pub fn run(args: DemoArgs) -> Result<()> {
    anyhow::ensure!(
        args.rate.is_finite() && args.rate > 0.0,
        "--rate must be a positive number of frames per second"
    );
    anyhow::ensure!(
        args.seconds.is_finite() && args.seconds >= 0.0,
        "--seconds must be a non-negative number"
    );
    let (cols, rows) = crate::parse::grid(&args.grid)?;
    let scene = MovingSpheres {
        points: args.points,
        ..Default::default()
    };
    let mut fitter = SurrogateFitter::new(FitOptions {
        cols,
        rows,
        sides: Sides::Sandwich,
        ..Default::default()
    })?;
    let period = Duration::from_secs_f64(1.0 / args.rate);
    let start = Instant::now();
    let (mut fit_ms, mut frames, mut next_report) = (Vec::new(), 0u64, 1.0);
    println!(
        "shroud demo: {} moving-sphere points at {} Hz, {}x{} sandwich, {} s",
        args.points, args.rate, cols, rows, args.seconds
    );
    while start.elapsed().as_secs_f64() < args.seconds {
        let tick = Instant::now();
        let points = scene.generate(start.elapsed().as_secs_f64())?;
        let fit_start = Instant::now();
        let surrogate = fitter.fit(&points)?;
        fit_ms.push(fit_start.elapsed().as_secs_f64() * 1e3);
        frames += 1;
        let now = start.elapsed().as_secs_f64();
        if now >= next_report {
            println!("{}", summary(now, frames, &mut fit_ms, &surrogate));
            next_report += 1.0;
        }
        std::thread::sleep(period.saturating_sub(tick.elapsed()));
    }
    Ok(())
}

fn summary(now: f64, frames: u64, fit_ms: &mut Vec<f64>, s: &Surrogate) -> String {
    let rate = fit_ms.len() as f64;
    let p50 = median(fit_ms);
    fit_ms.clear();
    let certs: Vec<String> = s
        .surfaces()
        .map(|x| {
            let c = &x.certificate;
            format!(
                "{:?} {} pts {} viol min gap {:.2e}",
                c.side, c.points_checked, c.violations, c.min_gap
            )
            .to_lowercase()
        })
        .collect();
    format!(
        "t={now:5.1}s frame {frames:5} {rate:4.0} Hz fit p50 {p50:6.2} ms | {}",
        certs.join(" | ")
    )
}
