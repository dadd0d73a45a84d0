use rand::{Rng, SeedableRng};
use shroud_core::spline::UniformCubicSurface;
use shroud_core::surrogate::*;
use shroud_core::tight::*;
fn main() {
    let trials: usize = std::env::args().nth(1).and_then(|s| s.parse().ok()).unwrap_or(200);
    let mut bad = 0;
    let mut max_it = 0;
    let first: u64 = std::env::args().nth(2).and_then(|s| s.parse().ok()).unwrap_or(0);
    for seed in first..first + trials as u64 {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(seed);
        let cols = rng.random_range(2..14);
        let rows = rng.random_range(2..14);
        let mut trim = TrimMask::empty(cols - 1, rows - 1);
        let density: f64 = rng.random_range(0.0..1.0);
        let m = rng.random_range(1..400);
        let quantize = rng.random_bool(0.3);
        let scale: f64 = [1e-3, 1.0, 1e3][rng.random_range(0..3)];
        let offset: f64 = [0.0, 100.0, -1e4][rng.random_range(0..3)];
        let mut cands = vec![];
        for _ in 0..m {
            let mut s = rng.random_range(0.0..(cols - 1) as f64);
            let mut t = rng.random_range(0.0..(rows - 1) as f64);
            if quantize { s = (s * 4.0).round() / 4.0; t = (t * 4.0).round() / 4.0; }
            if rng.random_range(0.0..1.0) > density && !cands.is_empty() { continue; }
            let h = offset + scale * ((s * 0.7).sin() + (t * 1.3).cos() + if rng.random_bool(0.1) { 2.0 } else { 0.0 });
            trim.mark(s, t);
            cands.push(Candidate { s, t, height: h });
        }
        let start_height = offset + scale * rng.random_range(-5.0..5.0);
        let surface = UniformCubicSurface::constant(cols, rows, start_height).unwrap();
        let lp = SplineLp::new(&surface, &trim, &cands).unwrap();
        let ipm = ipm::solve(&lp, &lp.gather(&surface.coefficients), &IpmSettings::default());
        let cl = lp_reference::solve_with_clarabel(&lp).map(|x| lp.objective(&x));
        match (&ipm, &cl) {
            (Ok(a), Ok(b)) => {
                max_it = max_it.max(a.iterations);
                let vol = (b - lp.cost.iter().sum::<f64>() * lp.heights.iter().fold(f64::INFINITY, |m, &v| m.min(v))).abs();
                let rel = (a.objective - b).abs() / vol.max(1e-300);
                if rel > 1e-6 && (a.objective - b).abs() > 1e-9 * b.abs() { bad += 1;
                    let xc = lp_reference::solve_with_clarabel(&lp).unwrap();
                    let fl = |x: &[f64]| x.iter().zip(&lp.floors).fold(f64::NEG_INFINITY, |m, (v, f)| m.max(f - v));
                    println!("   ipm: row viol {:e} floor viol {:e} max|x| {:e}; clarabel: row viol {:e} floor viol {:e} max|x| {:e}", lp.max_violation(&a.x), fl(&a.x), a.x.iter().fold(0.0f64, |m, v| m.max(v.abs())), lp.max_violation(&xc), fl(&xc), xc.iter().fold(0.0f64, |m, v| m.max(v.abs())));
                    println!("seed {seed}: {cols}x{rows} m {} ipm {} clarabel {b} rel {rel:e} it {}", lp.constraints(), a.objective, a.iterations); }
                if lp.max_violation(&a.x) > 0.0 { println!("seed {seed}: violation"); }
            }
            _ => { bad += 1; println!("seed {seed}: {cols}x{rows} m {} ipm {:?} clarabel {:?}", lp.constraints(), ipm.as_ref().map(|s| s.objective), cl); }
        }
    }
    println!("{bad} bad of {trials}, max iterations {max_it}");
}
