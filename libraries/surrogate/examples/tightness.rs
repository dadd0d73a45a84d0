//! How tight each mode is on every simulator scene, from three directions and on
//! both sides: excess volume over the data's envelope as a ratio to the exact LP
//! optimum over every point (clarabel and cutting planes, whose only lower bound
//! on the coefficients is one global safety floor far below the data), and the
//! fit times. Prints a markdown table, its caption holding the command.
//!
//! `cargo run --release -p shroud-surrogate --example tightness [points] [grid] [runs]`
//! (defaults: 30000 points, 20 x 20, 5 runs per mode; the reference takes about a
//! second a row at 30K points).

use shroud_sim::parts::part_by_name;
use shroud_sim::scanned_parts::ScannedShape;
use shroud_sim::Scene;
use shroud_surrogate::tight::{optimal_surface, CloudSide, Envelope, DEFAULT_RASTER};
use shroud_surrogate::{fit_surrogate, FitOptions, Side, Sides, Surrogate, Tightness};
use std::error::Error;
use std::time::{Instant, SystemTime, UNIX_EPOCH};

const MODES: [Tightness; 3] = [Tightness::Plain, Tightness::Lowered, Tightness::Optimal];

/// Viewing directions: straight down, tilted 30 degrees towards +y, and 60
/// degrees the other way (towards -x), so that the slanted views see the
/// scenes' walls and cliffs from different sides.
fn directions() -> [(&'static str, [f64; 3]); 3] {
    let (s30, c30) = 30f64.to_radians().sin_cos();
    let (s60, c60) = 60f64.to_radians().sin_cos();
    [
        ("down", [0.0, 0.0, -1.0]),
        ("30° to +y", [0.0, s30, -c30]),
        ("60° to -x", [-s60, 0.0, -c60]),
    ]
}

type Cloud = Vec<[f32; 3]>;

/// Every simulator scene usable as a static cloud, with about `points` points
/// (the scans: `points` rays; the crossing: the person's 6000 points and the
/// floor's).
fn scenes(points: usize) -> Result<Vec<(String, Cloud)>, Box<dyn Error>> {
    let mut out = Vec::new();
    for time in [0.0, 0.5, 1.0] {
        let spheres = Scene::by_name("moving-spheres", points, 0)?;
        out.push((format!("spheres t={time}"), spheres.generate(time)?));
    }
    for name in ["terrain", "table-top", "scan-table-top", "scan-terrain"] {
        out.push((
            name.to_owned(),
            Scene::by_name(name, points, 0)?.generate(0.0)?,
        ));
    }
    out.push((
        "crossing t=1".to_owned(),
        Scene::by_name("crossing", 6_000, 0)?.generate(1.0)?,
    ));
    out.push((
        "hemisphere".to_owned(),
        part_by_name("hemisphere", 0.5, points)?,
    ));
    out.push((
        "half-cylinder".to_owned(),
        part_by_name("half-cylinder", 0.5, points)?,
    ));
    for shape in [ScannedShape::LopsidedCap, ScannedShape::Band] {
        out.push((shape.name().to_owned(), shape.sample(0.5, points, 7)));
    }
    Ok(out)
}

fn main() -> Result<(), Box<dyn Error>> {
    let arg = |i: usize, default: usize| {
        std::env::args()
            .nth(i)
            .and_then(|s| s.parse().ok())
            .unwrap_or(default)
    };
    let (points, grid, runs) = (arg(1, 30_000), arg(2, 20), arg(3, 5).max(1));
    println!(
        "Excess volume over the data's envelope as a ratio to the global-floor LP optimum, \
         {grid} x {grid}, {runs} fits per mode (median ms), {}: \
         `cargo run --release -p shroud-surrogate --example tightness {points} {grid} {runs}`\n",
        utc_now()
    );
    println!("| scene | N | direction | side | plain | default | tight | plain ms | default ms | tight ms | reference |");
    println!("|---|---:|---|---|---:|---:|---:|---:|---:|---:|---|");
    for (scene, cloud) in scenes(points)? {
        for (direction_name, direction) in directions() {
            for side in [Side::Upper, Side::Lower] {
                let options = FitOptions {
                    cols: grid,
                    rows: grid,
                    direction,
                    sides: sides_of(side),
                    ..Default::default()
                };
                let cells = match row(&cloud, &options, side, runs) {
                    Ok(cells) => cells,
                    Err(e) => format!("| | | | | | | failed: {e} |"),
                };
                println!(
                    "| {scene} | {} | {direction_name} | {side:?} {cells}",
                    cloud.len()
                );
            }
        }
    }
    Ok(())
}

fn sides_of(side: Side) -> Sides {
    match side {
        Side::Upper => Sides::Upper,
        Side::Lower => Sides::Lower,
    }
}

/// The table cells after the side: the three ratios, the three times, and how
/// the reference was found.
fn row(
    cloud: &[[f32; 3]],
    options: &FitOptions,
    side: Side,
    runs: usize,
) -> Result<String, Box<dyn Error>> {
    let mut fits = Vec::new();
    for tightness in MODES {
        let opts = FitOptions {
            tightness,
            ..options.clone()
        };
        fits.push(timed_fit(cloud, &opts, runs)?);
    }
    let plain = &fits[0].0;
    let cloud_side = CloudSide::of(plain, cloud, side);
    let envelope = Envelope::new(&cloud_side, DEFAULT_RASTER, options.sub_cells);
    let start = Instant::now();
    let optimum = optimal_surface(
        &cloud_side,
        &surface_of(plain, side)?.surface,
        options.sub_cells,
    )?;
    let seconds = start.elapsed().as_secs_f64();
    let best = envelope.excess(&optimum.surface);
    let mut cells = String::new();
    for (fit, _) in &fits {
        let excess = envelope.excess(&surface_of(fit, side)?.surface);
        // The optimum dives below the data's level wherever only a curve of
        // the domain holds points (a wall seen edge-on): no ratio then.
        cells += &match best > 0.0 {
            true => format!("| {:.3} ", excess / best),
            false => "| n/a ".to_owned(),
        };
    }
    for (_, ms) in &fits {
        cells += &format!("| {ms:.2} ");
    }
    cells += &format!(
        "| excess {best:.4}; {} rounds, {} rows, {} of {} at the floor, {seconds:.1} s |",
        optimum.rounds, optimum.constraints, optimum.at_floor, optimum.unknowns
    );
    Ok(cells)
}

fn surface_of(surrogate: &Surrogate, side: Side) -> Result<&shroud_surrogate::SafeSurface, String> {
    match side {
        Side::Upper => surrogate.upper.as_ref(),
        Side::Lower => surrogate.lower.as_ref(),
    }
    .ok_or_else(|| format!("no {side:?} surface"))
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

/// The current UTC date and time, `YYYY-MM-DD HH:MM UTC` (days to civil date
/// after Howard Hinnant's `civil_from_days`).
fn utc_now() -> String {
    let secs = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| d.as_secs()) as i64;
    let (days, rem) = (secs.div_euclid(86_400), secs.rem_euclid(86_400));
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}-{month:02}-{day:02} {:02}:{:02} UTC",
        rem / 3600,
        rem % 3600 / 60
    )
}
