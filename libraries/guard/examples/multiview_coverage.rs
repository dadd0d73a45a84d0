//! How much tighter several views make the guard: on the simulator's table-top
//! scene, spheres sampled uniformly in the workspace above the table are
//! checked against sandwiches seen from the top, the front and the side, and
//! compared with the brute-force truth (no cloud point inside the sphere).
//!
//! `cargo run --release -p shroud-guard --example multiview_coverage` prints the
//! table in docs/node-graph.md: per radius, the share of truly free spheres that 1, 2 and 3
//! views prove clear, and how many they wrongly prove clear (always 0).

use glam::DVec3;
use rand::{Rng, SeedableRng};
use shroud_guard::{
    CollisionGuard, Envelope, GuardConfig, GuardPolicy, Shape, SurrogateInput, UnobservedPolicy,
    WorldShape,
};
use shroud_surrogate::{fit_surrogate, FitOptions, Sides};

const SPHERES: usize = 4000;
const RADII: [f64; 3] = [0.05, 0.1, 0.2];
const VIEWS: [(&str, [f64; 3]); 3] = [
    ("top", [0.0, 0.0, -1.0]),
    ("front", [0.0, 1.0, 0.0]),
    ("side", [1.0, 0.0, 0.0]),
];

type Error = Box<dyn std::error::Error>;

fn main() -> Result<(), Error> {
    let scene = shroud_sim::TableTop::default();
    let points = scene.generate()?;
    let cloud: Vec<DVec3> = points
        .iter()
        .map(|p| DVec3::new(p[0].into(), p[1].into(), p[2].into()))
        .collect();
    println!(
        "table-top scene, {} points; {SPHERES} spheres per radius, uniform in [-4, 4] x [-3, 3] x [0, 1.6]",
        points.len()
    );
    for grid in [16, 32] {
        println!("\n{grid} x {grid} sandwiches:\n");
        table(&points, &cloud, grid)?;
    }
    Ok(())
}

/// The guards over the first 1, 2 and 3 views of the cloud on a `grid`.
fn guards(points: &[[f32; 3]], grid: usize) -> Result<Vec<CollisionGuard>, Error> {
    let mut inputs = Vec::new();
    for (_, direction) in VIEWS {
        let options = FitOptions {
            cols: grid,
            rows: grid,
            direction,
            sides: Sides::Sandwich,
            ..FitOptions::default()
        };
        let surrogate = fit_surrogate(points, &options)?;
        inputs.push(SurrogateInput {
            envelope: Envelope::new(&surrogate)?,
            stamp_ns: 0,
            sequence: 0,
            pipeline_ns: 0,
            published_ns: 0,
            position_error: 0.0,
        });
    }
    // Stop distance 0: "proven clear" means a clearance above zero.
    let config = GuardConfig {
        stop_distance: 0.0,
        max_report: 0.5,
        ..GuardConfig::default()
    };
    let policy = GuardPolicy {
        max_skew_ns: u64::MAX,
        unobserved: UnobservedPolicy::Ignore,
        ..GuardPolicy::default()
    };
    (1..=VIEWS.len())
        .map(|count| {
            let names = VIEWS[..count].iter().map(|(n, _)| n.to_string()).collect();
            let mut guard = CollisionGuard::new(names, vec!["probe".into()], policy, config)?;
            for (v, input) in inputs.iter().take(count).enumerate() {
                guard.accept(v, input.clone(), 0, 0)?;
            }
            Ok(guard)
        })
        .collect()
}

/// One table: per radius, the truly free share and what each guard proves.
fn table(points: &[[f32; 3]], cloud: &[DVec3], grid: usize) -> Result<(), Error> {
    let guards = guards(points, grid)?;
    println!("| radius | truly free (of all spheres) | proven clear (of the truly free): top | top + front | top + front + side | wrongly proven clear |");
    println!("|---|---|---|---|---|---|");
    let mut rng = rand_pcg::Pcg64::seed_from_u64(2026);
    for radius in RADII {
        let mut free = 0usize;
        let mut proven = [0usize; 3];
        let mut wrong = 0usize;
        for _ in 0..SPHERES {
            let centre = DVec3::new(
                rng.random_range(-4.0..4.0),
                rng.random_range(-3.0..3.0),
                rng.random_range(0.0..1.6),
            );
            let truly_free = cloud.iter().all(|p| p.distance(centre) > radius);
            free += usize::from(truly_free);
            let shape = [WorldShape {
                link: 0,
                shape: Shape::sphere(centre, radius),
            }];
            for (k, guard) in guards.iter().enumerate() {
                let decision = guard.decide(&shape, 0)?;
                let clear = decision.report.is_some_and(|r| r.min_clearance > 0.0);
                proven[k] += usize::from(clear);
                wrong += usize::from(clear && !truly_free);
            }
        }
        let share = |n: usize| 100.0 * n as f64 / free.max(1) as f64;
        println!(
            "| {radius} | {:.1}% | {:.1}% | {:.1}% | {:.1}% | {wrong} |",
            100.0 * free as f64 / SPHERES as f64,
            share(proven[0]),
            share(proven[1]),
            share(proven[2]),
        );
        if wrong > 0 {
            return Err(format!("{wrong} spheres wrongly proven clear").into());
        }
    }
    Ok(())
}
