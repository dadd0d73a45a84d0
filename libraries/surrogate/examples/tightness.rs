//! How tight each mode is: excess volume over the data (ratio to the exact LP
//! optimum over every point) and fit time, on the paper's moving spheres and on
//! the terrain with cliffs. Prints a markdown table.
//!
//! `cargo run --release -p shroud-surrogate --example tightness [points] [grid] [runs]`
//! (defaults: 300000 points, 20 x 20, 11 runs per mode).

use shroud_surrogate::tight::{optimal_surface, CloudSide, Envelope, DEFAULT_RASTER};
use shroud_surrogate::{fit_surrogate, FitOptions, Side, Surrogate, Tightness};
use std::error::Error;
use std::time::Instant;

const MODES: [(&str, Tightness); 3] = [
    ("plain", Tightness::Plain),
    ("lowered", Tightness::Lowered),
    ("optimal", Tightness::Optimal),
];

fn main() -> Result<(), Box<dyn Error>> {
    let arg = |i: usize, default: usize| {
        std::env::args()
            .nth(i)
            .and_then(|s| s.parse().ok())
            .unwrap_or(default)
    };
    let (points, grid, runs) = (arg(1, 300_000), arg(2, 20), arg(3, 11).max(1));
    let spheres = shroud_sim::MovingSpheres {
        points,
        ..Default::default()
    };
    let scenes = [
        ("spheres t=0.0".to_owned(), spheres.generate(0.0)?),
        ("spheres t=0.3".to_owned(), spheres.generate(0.3)?),
        ("spheres t=1.0".to_owned(), spheres.generate(1.0)?),
        (
            "terrain".to_owned(),
            shroud_sim::Terrain {
                points,
                ..Default::default()
            }
            .generate()?,
        ),
    ];
    println!("| scene | N | grid | plain | lowered | optimal | plain ms | lowered ms | optimal ms | reference |");
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for (name, cloud) in &scenes {
        let options = FitOptions {
            cols: grid,
            rows: grid,
            ..Default::default()
        };
        let mut ratios = Vec::new();
        let mut times = Vec::new();
        let mut reference_note = String::new();
        for (_, tightness) in MODES {
            let opts = FitOptions {
                tightness,
                ..options.clone()
            };
            let (surrogate, ms) = timed_fit(cloud, &opts, runs)?;
            if tightness == Tightness::Plain {
                reference_note = reference(&surrogate, cloud, &opts, &mut ratios)?;
            }
            ratios.push(excess_of(&surrogate, cloud, &opts)?);
            times.push(ms);
        }
        let optimum = ratios[0];
        println!(
            "| {name} | {} | {grid}x{grid} | {:.3} | {:.3} | {:.3} | {:.2} | {:.2} | {:.2} | {reference_note} |",
            cloud.len(),
            ratios[1] / optimum,
            ratios[2] / optimum,
            ratios[3] / optimum,
            times[0],
            times[1],
            times[2]
        );
    }
    Ok(())
}

/// Median fit time (ms) over `runs` cold fits, and the last surrogate.
fn timed_fit(
    cloud: &[[f32; 3]],
    options: &FitOptions,
    runs: usize,
) -> Result<(Surrogate, f64), Box<dyn Error>> {
    let mut times = Vec::with_capacity(runs);
    let mut last = None;
    for _ in 0..runs {
        let start = Instant::now();
        let surrogate = fit_surrogate(cloud, options)?;
        times.push(start.elapsed().as_secs_f64() * 1e3);
        last = Some(surrogate);
    }
    times.sort_by(f64::total_cmp);
    let surrogate = last.ok_or("no run")?;
    Ok((surrogate, times[times.len() / 2]))
}

/// Pushes the optimum's excess volume first and describes the reference solve.
fn reference(
    surrogate: &Surrogate,
    cloud: &[[f32; 3]],
    options: &FitOptions,
    excesses: &mut Vec<f64>,
) -> Result<String, Box<dyn Error>> {
    let upper = surrogate.upper.as_ref().ok_or("no upper surface")?;
    let side = CloudSide::of(surrogate, cloud, Side::Upper);
    let start = Instant::now();
    let optimum = optimal_surface(&side, &upper.surface, options.sub_cells)?;
    let seconds = start.elapsed().as_secs_f64();
    excesses.push(Envelope::new(&side, DEFAULT_RASTER, options.sub_cells).excess(&optimum.surface));
    Ok(format!(
        "{} rounds, {} rows, {seconds:.1} s",
        optimum.rounds, optimum.constraints
    ))
}

fn excess_of(
    surrogate: &Surrogate,
    cloud: &[[f32; 3]],
    options: &FitOptions,
) -> Result<f64, Box<dyn Error>> {
    let upper = surrogate.upper.as_ref().ok_or("no upper surface")?;
    let side = CloudSide::of(surrogate, cloud, Side::Upper);
    Ok(Envelope::new(&side, DEFAULT_RASTER, options.sub_cells).excess(&upper.surface))
}
