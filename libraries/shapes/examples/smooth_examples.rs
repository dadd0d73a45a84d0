//! The experiments of paper 004 (Marsala, Mantzaflaris, Mourrain), Section 6.1,
//! beside the paper's tables: Example 1 (f_T over M_T and its four
//! Catmull-Clark refinements, 150528 points, lambda = 0) and Example 2 (f_E over
//! the 96-patch hexagon, 153600 points, four smoothing weights) and Example 3
//! (a radial function over the 96-face cube-sphere, 540000 points).
//!
//! `cargo run --release -p shroud-shapes --example smooth_examples`

use shroud_shapes::mesh::{
    catmull_clark, hexagon_mesh as hexagon, triangle_mesh as m_t, G1Domain, QuadMesh,
};
use shroud_shapes::smooth::{cube_sphere, PlanarLocator, SmoothFitter, SphereLocator};
use std::time::Instant;

/// `per_side^2` points per face of `mesh` on a regular parameter grid, mapped
/// to the plane by each face's bilinear map.
fn grid_points(mesh: &QuadMesh, per_side: usize) -> Vec<[f64; 2]> {
    let v = mesh.vertices();
    let mut out = Vec::new();
    for quad in mesh.faces() {
        let p = |k: usize| v[quad[k] as usize];
        for b in 0..per_side {
            for a in 0..per_side {
                let (u, w) = (
                    (a as f64 + 0.5) / per_side as f64,
                    (b as f64 + 0.5) / per_side as f64,
                );
                let weights = [(1.0 - u) * (1.0 - w), u * (1.0 - w), u * w, (1.0 - u) * w];
                let x = (0..4).map(|k| weights[k] * p(k)[0]).sum();
                let y = (0..4).map(|k| weights[k] * p(k)[1]).sum();
                out.push([x, y]);
            }
        }
    }
    out
}

fn refine(mesh: QuadMesh, times: usize) -> QuadMesh {
    (0..times).fold(mesh, |m, _| catmull_clark(&m).expect("refine"))
}

/// Fits `values` at `xy` over `mesh`; returns (dimension, errors, seconds).
fn fit(
    mesh: QuadMesh,
    xy: &[[f64; 2]],
    values: &[f64],
    lambda: f64,
) -> (usize, [f64; 3], f64, f64) {
    let start = Instant::now();
    let locator = PlanarLocator::new(&mesh).expect("planar");
    let samples = locator.locate_all(xy).expect("inside the domain");
    let fitter = SmoothFitter::new(G1Domain::new(mesh).expect("domain")).expect("basis");
    let basis_s = start.elapsed().as_secs_f64();
    let surface = fitter.fit(&samples, values, 1, lambda).expect("fit");
    let total = start.elapsed().as_secs_f64();
    let e = surface.errors(&samples, values);
    (fitter.basis.len(), [e.min, e.max, e.rmse], basis_s, total)
}

fn main() {
    println!("# G1 smooth fitting (paper 004), Section 6.1\n");
    println!("{} rayon threads\n", rayon::current_num_threads());

    // f_T of eq. (29), read as (y / 2) cos(4 (x^2 + y - 1)).
    let f_t = |p: &[f64; 2]| p[1] / 2.0 * (4.0 * (p[0] * p[0] + p[1] - 1.0)).cos();
    let xy = grid_points(&m_t(), 224);
    let values: Vec<f64> = xy.iter().map(f_t).collect();
    println!(
        "## Example 1: f_T over M_T, {} points, lambda = 0 (Table 1)\n",
        xy.len()
    );
    println!("| dim | paper min | shroud min | paper L-inf | shroud L-inf | paper RMSE | shroud RMSE | basis (s) | total (s) |");
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let paper = [
        (2.331e-05, 0.364, 0.491e-01),
        (2.070e-06, 0.122, 0.149e-01),
        (2.836e-08, 0.834e-01, 0.335e-02),
        (5.328e-11, 0.178e-01, 0.353e-03),
        (3.364e-14, 0.790e-02, 0.570e-06),
    ];
    for (level, (pm, pl, pr)) in paper.iter().enumerate() {
        let (dim, e, basis_s, total) = fit(refine(m_t(), level), &xy, &values, 0.0);
        println!(
            "| {dim} | {pm:.3e} | {:.3e} | {pl:.3e} | {:.3e} | {pr:.3e} | {:.3e} | {basis_s:.2} | {total:.2} |",
            e[0], e[1], e[2]
        );
    }

    // f_E of eq. (30) over the 96-patch hexagon.
    let f_e = |p: &[f64; 2]| {
        [-3.0, 0.0, 3.0]
            .iter()
            .map(|nu| {
                let r = ((10.0 * p[0] + nu).powi(2) + (10.0 * p[1] + nu).powi(2)).sqrt();
                2.0 / (3.0 * r.exp())
            })
            .sum::<f64>()
    };
    let hex = hexagon();
    let xy = grid_points(&hex, 160);
    let values: Vec<f64> = xy.iter().map(f_e).collect();
    println!(
        "\n## Example 2: f_E over the 96-patch hexagon, {} points (Table 2)\n",
        xy.len()
    );
    println!("| lambda | dim | paper min | shroud min | paper L-inf | shroud L-inf | paper RMSE | shroud RMSE | total (s) |");
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let paper = [
        (0.0, 1.248e-11, 0.164, 0.308e-02),
        (1e-3, 1.457e-09, 0.165, 0.310e-02),
        (1e-2, 2.308e-09, 0.170, 0.312e-02),
        (1e-1, 3.260e-08, 0.196, 0.375e-02),
    ];
    for (lambda, pm, pl, pr) in paper {
        let (dim, e, _, total) = fit(refine(hex.clone(), 2), &xy, &values, lambda);
        println!(
            "| {lambda} | {dim} | {pm:.3e} | {:.3e} | {pl:.3e} | {:.3e} | {pr:.3e} | {:.3e} | {total:.2} |",
            e[0], e[1], e[2]
        );
    }

    example_3();
}

/// Example 3: f_S2 of eq. (31) as a radial function r(direction) over the
/// 96-face cube-sphere, 540000 directions spread by a Fibonacci lattice.
fn example_3() {
    let tau = std::f64::consts::TAU;
    let f = |d: &[f64; 3]| {
        (0.0f64).max((tau * d[0]).sin() * (tau * d[1]).sin() * (tau * d[2]).sin()) + 1.0
    };
    let n = 540_000;
    let directions: Vec<[f64; 3]> = shroud_geometry::math::fibonacci_sphere(n)
        .iter()
        .map(|d| d.to_array())
        .collect();
    let values: Vec<f64> = directions.iter().map(f).collect();
    let start = Instant::now();
    let mesh = cube_sphere(2).expect("cube-sphere");
    let samples = SphereLocator::new(&mesh)
        .locate_all(&directions)
        .expect("directions");
    let fitter = SmoothFitter::new(G1Domain::new(mesh).expect("domain")).expect("basis");
    let surface = fitter.fit(&samples, &values, 1, 0.0).expect("fit");
    let seconds = start.elapsed().as_secs_f64();
    let e = surface.errors(&samples, &values);
    println!("\n## Example 3: f_S2 over the 96-face sphere, {n} points (Table 3)\n");
    println!("| dim | paper min | shroud min | paper L-inf | shroud L-inf | paper RMSE | shroud RMSE | total (s) |");
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|");
    println!(
        "| {} | 1.028e-5 | {:.3e} | 5.390e-2 | {:.3e} | 1.070e-2 | {:.3e} | {seconds:.2} |",
        fitter.basis.len(),
        e.min,
        e.max,
        e.rmse
    );
}
