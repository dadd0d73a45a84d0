use shroud_core::surrogate::*;
use shroud_core::tight::*;
use std::time::Instant;
fn main() {
    let reps: usize = std::env::args().nth(1).and_then(|s| s.parse().ok()).unwrap_or(20);
    let scene = std::env::args().nth(2).unwrap_or("terrain".into());
    let fits = std::env::args().nth(3).is_some();
    let pts = if scene == "terrain" { shroud_sim::Terrain { points: 300_000, ..Default::default() }.generate().unwrap() } else { shroud_sim::MovingSpheres { points: 300_000, ..Default::default() }.generate(0.3).unwrap() };
    let s = fit_surrogate(&pts, &FitOptions { tightness: Tightness::Plain, ..Default::default() }).unwrap();
    let side = CloudSide::of(&s, &pts, Side::Upper);
    let up = &s.upper.as_ref().unwrap().surface;
    let idx = lp_reference::candidate_indices(&side, 4);
    let all: Vec<Candidate> = side.constraints().collect();
    let cands: Vec<Candidate> = idx.iter().map(|&i| all[i as usize]).collect();
    let mut best = f64::INFINITY;
    let mut it = 0;
    let mut obj = 0.0;
    let t0 = Instant::now();
    for _ in 0..reps {
        let t1 = Instant::now();
        let lp = SplineLp::new(up, &s.trim, &cands).unwrap();
        let sol = ipm::solve(&lp, &lp.gather(&up.coefficients), &IpmSettings { gap: std::env::args().nth(4).and_then(|s| s.parse().ok()).unwrap_or(1e-7), feasibility: std::env::args().nth(5).and_then(|s| s.parse().ok()).unwrap_or(1e-7), max_iterations: 60 }).unwrap();
        best = best.min(t1.elapsed().as_secs_f64()*1e3);
        it = sol.iterations; obj = sol.objective;
    }
    println!("IPM min {:.2} ms mean {:.2}, {} iterations, objective {obj:.9}, {} candidates", best, t0.elapsed().as_secs_f64()*1e3/reps as f64, it, cands.len());
    if !fits { return; }
    for t in [Tightness::Plain, Tightness::Lowered, Tightness::Optimal] {
        let mut times = vec![];
        let mut last = None;
        for _ in 0..reps { let t0 = Instant::now(); last = Some(fit_surrogate(&pts, &FitOptions { tightness: t, ..Default::default() }).unwrap()); times.push(t0.elapsed().as_secs_f64()*1e3); }
        times.sort_by(f64::total_cmp);
        let c = &last.unwrap().upper.unwrap().certificate;
        println!("{t:?}: median {:.2} min {:.2} corrected {}", times[reps/2], times[0], c.corrected_points);
    }
}
