//! The measures of the point-cloud blender (paper 001): timing beside the paper's
//! Table 1 and quality (seam gaps, overlap rates) on pairs built from analytic
//! shapes and the simulator's scenes.
//!
//! `cargo run --release -p shroud-shapes --example blend_measures`

#[path = "../tests/blend_scenes/mod.rs"]
mod blend_scenes;

use blend_scenes::*;
use glam::DVec3;
use shroud_geometry::cloud::{BoundaryParams, NeighbourIndex};
use shroud_shapes::blend::{
    blend, blend_sequence, overlap_rate, seam_gap, seam_points, Blend, BlendParams, Child,
    LocalAdjust, Merged, Prepared, Source,
};
use std::time::Instant;

struct Pair {
    name: &'static str,
    parent: Prepared,
    child: Child,
    at: DVec3,
    adjust: LocalAdjust,
}

fn child(points: &[[f32; 3]]) -> Child {
    let cloud = Prepared::new(points, "child", 12).expect("child cloud");
    Child::new(cloud, None, &BoundaryParams::default()).expect("child boundary")
}

fn pairs() -> Vec<Pair> {
    let plane = || Prepared::new(&plane(2.0, 20_000, 0.0, 1), "parent", 12).expect("plane");
    vec![
        Pair {
            name: "hemisphere r0.5 on plane",
            parent: plane(),
            child: child(&hemisphere(0.5, 4_000)),
            at: DVec3::new(0.2, -0.1, 0.0),
            adjust: LocalAdjust::default(),
        },
        Pair {
            name: "sim sphere cap on sim terrain hill",
            parent: Prepared::new(&sim_terrain(30_000, 2), "parent", 12).expect("terrain"),
            child: child(&sim_cap(0.5, 0.3, 6_000, 4)),
            at: DVec3::new(-1.5, -1.0, 1.0),
            adjust: LocalAdjust::default(),
        },
        Pair {
            name: "half-cylinder on sim table top",
            parent: Prepared::new(&sim_table(30_000, 3), "parent", 12).expect("table"),
            child: child(&half_cylinder(0.3, 1.2, 5_000, 5)),
            at: DVec3::new(-0.3, -1.1, 0.0),
            adjust: LocalAdjust {
                spin: 0.4,
                ..Default::default()
            },
        },
        Pair {
            name: "hemisphere r0.35 on sim sphere R1",
            parent: Prepared::new(&sim_sphere(1.0, [0.0; 3], 20_000, 6), "parent", 12)
                .expect("sphere"),
            child: child(&hemisphere(0.35, 3_000)),
            at: DVec3::new(0.3, 0.2, 1.0),
            adjust: LocalAdjust::default(),
        },
    ]
}

fn run(pair: &Pair, params: &BlendParams) -> Blend {
    let (p_t, v_t) = pair
        .parent
        .surface_pair(pair.at, 16)
        .expect("drop point on the surface");
    let placement = pair.child.placement(p_t, v_t, &pair.adjust);
    blend(&pair.parent, &pair.child, &placement, params).expect("blend")
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn timing() {
    println!("## Timing beside the paper's Table 1\n");
    println!(
        "Blend = regions + normals + RBF (greedy, dense LBL^T) + marching tetrahedra + merge;"
    );
    println!(
        "the clouds' kd-trees and normals are prepared once per drag session (column 'prepare').\n"
    );
    println!("| scene | points in model | points in blending region | RBF centres | points in transition region | blending time (ms, median of 7) | regions | normals | RBF | sampling | merge | prepare (ms) | paper |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|");
    let hemi = hemisphere(0.5, 4_000);
    let flat = plane(2.0, 20_000, 0.0, 1);
    let t = Instant::now();
    let pair = Pair {
        name: "hemisphere on plane",
        parent: Prepared::new(&flat, "parent", 12).expect("plane"),
        child: child(&hemi),
        at: DVec3::new(0.2, -0.1, 0.0),
        adjust: LocalAdjust::default(),
    };
    let prepare = t.elapsed().as_secs_f64() * 1e3;
    let papers = [
        (617, 16_463, "Fig. 11a: 617 centres, 16 463 points, 25 s"),
        (309, 1_191, "Fig. 11b: 309 centres, 1 191 points, 7 s"),
        (337, 3_383, "Fig. 11c: 337 centres, 3 383 points, 8 s"),
    ];
    for (centres, target, paper) in papers {
        let mut params = BlendParams::default();
        params.rbf.max_centres = centres;
        params.rbf.initial_centres = centres.min(160);
        // Calibrate the cell so that T_R has about `target` points.
        for _ in 0..3 {
            let got = run(&pair, &params).report.transition_points as f64;
            params.cell *= (got / target as f64).sqrt();
        }
        let mut last = None;
        let times: Vec<f64> = (0..7)
            .map(|_| {
                let b = run(&pair, &params);
                let t = b.report.times.total;
                last = Some(b);
                t
            })
            .collect();
        let b = last.expect("seven runs");
        let r = &b.report;
        let s = r.times;
        println!(
            "| {} ({centres} centres) | {} | {} | {} | {} | **{:.1}** | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {prepare:.0} | {paper} |",
            pair.name,
            flat.len() + hemi.len(),
            r.parent_region + r.child_region,
            r.greedy.centres,
            r.transition_points,
            median(times),
            s.regions,
            s.normals,
            s.rbf,
            s.sampling,
            s.merge
        );
    }
    println!();
}

fn quality() {
    println!("## Quality: seam gaps and overlap rates\n");
    println!(
        "Seam points: F_p within 2 spacings inside P_out, F_c within 2 spacings below P_front."
    );
    println!("Surface gap = |s|/|grad s| (distance to the transition surface), sampled gap = distance to the");
    println!("nearest T_R sample; both in units of the parent's spacing h. Overlap rate: fraction of points with a");
    println!("point of another source (parent/child/transition) closer than h/2; union = M_p + M_c + T_R.\n");
    println!("| pair | h | F_p / F_c | centres | T_R kept / sampled | parent seam: surface gap mean / max | sampled max | child seam: surface gap mean / max | sampled max | overlap union | overlap merged | time (ms) |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let params = BlendParams::default();
    for pair in pairs() {
        let b = run(&pair, &params);
        let h = pair.parent.spacing;
        let tr = NeighbourIndex::new(
            b.merged
                .points
                .iter()
                .zip(&b.merged.sources)
                .filter(|(_, s)| **s == Source::Transition)
                .map(|(p, _)| *p)
                .collect(),
        );
        let (sp, sc) = seam_points(&b, pair.parent.points(), 2.0 * h);
        let gp = seam_gap(&b.rbf, &sp, &tr);
        let gc = seam_gap(&b.rbf, &sc, &tr);
        let union = Merged::union([
            (pair.parent.points(), &b.parent_normals, Source::Parent),
            (&b.child_points, &b.child_normals, Source::Child),
            (
                &b.transition.points,
                &b.transition.normals,
                Source::Transition,
            ),
        ]);
        let r = &b.report;
        println!(
            "| {} | {:.4} | {} / {} | {} | {} / {} | {:.3} / {:.3} | {:.2} | {:.3} / {:.3} | {:.2} | {:.1} % | {:.2} % | {:.0} |",
            pair.name,
            h,
            r.parent_region,
            r.child_region,
            r.greedy.centres,
            r.kept_transition,
            r.transition_points,
            gp.surface_mean / h,
            gp.surface_max / h,
            gp.sampled_max / h,
            gc.surface_mean / h,
            gc.surface_max / h,
            gc.sampled_max / h,
            100.0 * overlap_rate(&union, 0.5 * h),
            100.0 * overlap_rate(&b.merged, 0.5 * h),
            r.times.total
        );
    }
    // Compound: two hemispheres and a half-cylinder dropped in turn on the plane.
    let parent = Prepared::new(&plane(2.0, 20_000, 0.0, 1), "parent", 12).expect("plane");
    let h = parent.spacing;
    let hemi = child(&hemisphere(0.4, 3_000));
    let cyl = child(&half_cylinder(0.3, 1.0, 4_000, 5));
    let drops = [
        (
            &hemi,
            hemi.placement(
                DVec3::new(-1.0, 0.6, 0.0),
                DVec3::Z,
                &LocalAdjust::default(),
            ),
        ),
        (
            &hemi,
            hemi.placement(DVec3::new(1.0, 0.6, 0.0), DVec3::Z, &LocalAdjust::default()),
        ),
        (
            &cyl,
            cyl.placement(
                DVec3::new(0.0, -0.9, 0.0),
                DVec3::Z,
                &LocalAdjust {
                    spin: 0.3,
                    ..Default::default()
                },
            ),
        ),
    ];
    let t = Instant::now();
    let (merged, reports) = blend_sequence(parent, &drops, &params).expect("compound blend");
    let ms = t.elapsed().as_secs_f64() * 1e3;
    println!(
        "| compound: 2 hemispheres + half-cylinder on plane | {h:.4} | {} | {} | {} | | | | | | {:.2} % (last step) | {ms:.0} (3 drops) |",
        reports.iter().map(|r| format!("{}/{}", r.parent_region, r.child_region)).collect::<Vec<_>>().join(", "),
        reports.iter().map(|r| r.greedy.centres.to_string()).collect::<Vec<_>>().join(", "),
        reports.iter().map(|r| r.kept_transition.to_string()).collect::<Vec<_>>().join(", "),
        100.0 * overlap_rate(&merged, 0.5 * h)
    );
    println!();
}

fn main() {
    println!("# Point-cloud blending measures (paper 001)\n");
    println!("{} rayon threads\n", rayon::current_num_threads());
    timing();
    quality();
}
