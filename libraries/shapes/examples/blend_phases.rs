//! Per-phase medians of one blend (paper 001): a simulated part dropped onto a
//! simulated scan, as `shroud blend` would do it with its default tunables.
//! Issue 27's case (a 6000-point open hemisphere onto a 14400-point scan) is the
//! default:
//!
//! `cargo run --release -p shroud-shapes --example blend_phases -- [runs] [scene] [scan rays] [part] [part size] [part points] [x,y,z] [centres] [split|direct]`
//!
//! defaults: 7 scan-table-top 19400 scanned-hemisphere 0.3 6000 -0.3,-1.1,0 1200 split
//! (19,400 rays of the table-top scan return 14,444 points; the scanned
//! hemisphere is the boundary sweep's random cap, rim 3 degrees above its base).
//! `direct` samples with the direct sum (the reference) instead of the split
//! evaluation; the last line says how far the sampled points lie from the
//! RBF's zero set.

use glam::DVec3;
use shroud_shapes::blend::{
    blend, BlendParams, Child, Evaluation, LocalAdjust, Prepared, StageTimes,
};
use shroud_sim::parts::part_by_name;
use shroud_sim::scanned_parts::SCANNED_SHAPES;
use shroud_sim::Scene;

struct Case {
    runs: usize,
    scene: String,
    scan_points: usize,
    part: String,
    part_size: f64,
    part_points: usize,
    at: DVec3,
    centres: usize,
    evaluation: Evaluation,
}

fn parse_case() -> Case {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |i: usize, default: &str| args.get(i).cloned().unwrap_or_else(|| default.into());
    let number = |i: usize, default: &str| -> f64 {
        arg(i, default)
            .parse()
            .unwrap_or_else(|_| panic!("argument {} is not a number", i + 1))
    };
    let at: Vec<f64> = arg(6, "-0.3,-1.1,0")
        .split(',')
        .map(|s| s.parse().expect("x,y,z"))
        .collect();
    assert_eq!(at.len(), 3, "the drop point is x,y,z");
    Case {
        runs: number(0, "7") as usize,
        scene: arg(1, "scan-table-top"),
        scan_points: number(2, "19400") as usize,
        part: arg(3, "scanned-hemisphere"),
        part_size: number(4, "0.3"),
        part_points: number(5, "6000") as usize,
        at: DVec3::new(at[0], at[1], at[2]),
        centres: number(7, "1200") as usize,
        evaluation: match arg(8, "split").as_str() {
            "direct" => Evaluation::Direct,
            _ => Evaluation::Split,
        },
    }
}

/// A part by name: the analytic parts of `shroud blend`'s node, or
/// `scanned-NAME` for a random scan of one of the boundary sweep's shapes.
fn part(case: &Case) -> Vec<[f32; 3]> {
    match case.part.strip_prefix("scanned-") {
        Some(name) => SCANNED_SHAPES
            .iter()
            .find(|s| s.name() == name)
            .expect("a scanned shape")
            .sample(case.part_size, case.part_points, 1),
        None => part_by_name(&case.part, case.part_size, case.part_points).expect("part"),
    }
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let case = parse_case();
    let scan = Scene::by_name(&case.scene, case.scan_points, 1)
        .and_then(|s| s.generate(0.0))
        .expect("scene");
    let part = part(&case);
    let parent = Prepared::new(&scan, "parent", 12).expect("parent");
    let cloud = Prepared::new(&part, "child", 12).expect("part cloud");
    let child = Child::new(cloud, None, &Default::default()).expect("part rim");
    let mut params = BlendParams::default();
    params.rbf.max_centres = case.centres;
    params.evaluation = case.evaluation;
    let (p_t, v_t) = parent.surface_pair(case.at, 16).expect("drop point");
    let placement = child.placement(p_t, v_t, &LocalAdjust::default());
    let runs: Vec<_> = (0..case.runs.max(1))
        .map(|_| blend(&parent, &child, &placement, &params).expect("blend"))
        .collect();
    let last = &runs[runs.len() - 1].report;
    println!(
        "{} {} points (spacing {:.4}) + {} {} points (spacing {:.4}), {} rayon threads",
        case.scene,
        scan.len(),
        parent.spacing,
        case.part,
        part.len(),
        child.cloud.spacing,
        rayon::current_num_threads()
    );
    println!("{:?} evaluation", case.evaluation);
    println!(
        "F_p {} + F_c {}: {} centres of {} constraints; {} cells visited, {} transition points ({} kept)",
        last.parent_region,
        last.child_region,
        last.greedy.centres,
        last.constraints,
        last.cells_visited,
        last.transition_points,
        last.kept_transition
    );
    let phase =
        |f: fn(&StageTimes) -> f64| median(runs.iter().map(|b| f(&b.report.times)).collect());
    println!("| total | regions | normals | RBF | sampling | merge |");
    println!("|---:|---:|---:|---:|---:|---:|");
    let last_blend = &runs[runs.len() - 1];
    let distances = last_blend
        .transition
        .points
        .iter()
        .map(|&p| last_blend.rbf.distance_estimate(p));
    let (worst, sum) = distances.fold((0.0f64, 0.0), |(m, s), d| (m.max(d), s + d));
    println!(
        "| **{:.1}** | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} |",
        phase(|t| t.total),
        phase(|t| t.regions),
        phase(|t| t.normals),
        phase(|t| t.rbf),
        phase(|t| t.sampling),
        phase(|t| t.merge)
    );
    println!(
        "transition points off the zero set (|s| / |grad s|): max {worst:.2e}, mean {:.2e}",
        sum / last_blend.transition.points.len().max(1) as f64
    );
}
