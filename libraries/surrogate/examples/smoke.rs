//! Smoke test of the fitter on the moving-sphere scene: median and best time of
//! repeated (warm-started) fits, Plain and Lowered, with the certificate and the
//! reduction's statistics of the last fit.
//!
//! `cargo run --release -p shroud-surrogate --example smoke [points grid reps]`
//! (defaults 300000 20 30).

use shroud_surrogate::*;
use std::time::Instant;

fn arg(position: usize, default: usize) -> usize {
    std::env::args()
        .nth(position)
        .and_then(|s| s.parse().ok())
        .unwrap_or(default)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (points, grid, reps) = (arg(1, 300_000), arg(2, 20), arg(3, 30).max(1));
    let scene = shroud_sim::MovingSpheres {
        points,
        ..Default::default()
    };
    let pts = scene.generate(0.3)?;
    for tightness in [Tightness::Plain, Tightness::Lowered] {
        let options = FitOptions {
            tightness,
            cols: grid,
            rows: grid,
            ..Default::default()
        };
        let mut fitter = SurrogateFitter::new(options)?;
        let mut times = Vec::with_capacity(reps);
        let mut last = None;
        for _ in 0..reps {
            let t0 = Instant::now();
            last = Some(fitter.fit(&pts)?);
            times.push(t0.elapsed().as_secs_f64() * 1e3);
        }
        times.sort_by(|a, b| a.total_cmp(b));
        let Some(surrogate) = last else { continue };
        for safe in surrogate.surfaces() {
            let c = &safe.certificate;
            println!(
                "{tightness:?} median {:.2} ms best {:.2} | {:?}: {} points checked, {} violations, \
                 gap min {:.3e} mean {:.4} max {:.4}, corrected {} | candidates {}, curve solves mean {:.1} max {}",
                times[reps / 2],
                times[0],
                safe.side,
                c.points_checked,
                c.violations,
                c.min_gap,
                c.mean_gap,
                c.max_gap,
                c.corrected_points,
                surrogate.stats.candidates,
                surrogate.stats.curve_solves.mean(),
                surrogate.stats.curve_solves.max()
            );
        }
    }
    Ok(())
}
