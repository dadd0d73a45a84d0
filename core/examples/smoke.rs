use shroud_core::surrogate::*;
use std::time::Instant;
fn main() {
    let n: usize = std::env::args().nth(1).and_then(|s| s.parse().ok()).unwrap_or(300_000);
    let grid: usize = std::env::args().nth(2).and_then(|s| s.parse().ok()).unwrap_or(20);
    let reps: usize = std::env::args().nth(3).and_then(|s| s.parse().ok()).unwrap_or(30);
    let scene = shroud_sim::MovingSpheres { points: n, ..Default::default() };
    let pts = scene.generate(0.3).unwrap();
    for tight in [Tightness::Plain, Tightness::Lowered] {
        let opts = FitOptions { tightness: tight, cols: grid, rows: grid, ..Default::default() };
        let mut fitter = SurrogateFitter::new(opts).unwrap();
        let mut times = vec![];
        let mut last = None;
        for _ in 0..reps {
            let t0 = Instant::now();
            let s = fitter.fit(&pts).unwrap();
            times.push(t0.elapsed().as_secs_f64() * 1e3);
            last = Some(s);
        }
        times.sort_by(|a, b| a.total_cmp(b));
        let s = last.unwrap();
        let c = &s.upper.as_ref().unwrap().certificate;
        println!("{tight:?} median {:.2} ms min {:.2} cert {:?} cand {} curve solves mean {:.1} max {} corrected {}", times[reps/2], times[0], (c.min_gap, c.mean_gap, c.max_gap, c.violations), s.stats.candidates, s.stats.curve_solves.mean(), s.stats.curve_solves.max(), c.corrected_points);
    }
}
