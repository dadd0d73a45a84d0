use shroud_core::surrogate::*;
use shroud_core::tight::*;
use std::time::Instant;
fn main() {
    let sp = shroud_sim::MovingSpheres { points: 300_000, ..Default::default() };
    let scenes = vec![("spheres0.3", sp.generate(0.3).unwrap()), ("terrain", shroud_sim::Terrain { points: 300_000, ..Default::default() }.generate().unwrap())];
    for (name, pts) in scenes {
        let s = fit_surrogate(&pts, &FitOptions { tightness: Tightness::Plain, ..Default::default() }).unwrap();
        let side = CloudSide::of(&s, &pts, Side::Upper);
        let env = Envelope::new(&side, 8, 4);
        let up = &s.upper.as_ref().unwrap().surface;
        let all: Vec<Candidate> = side.constraints().collect();
        let opt = optimal_surface(&side, up, 4).unwrap();
        let e_ref = env.excess(&opt.surface);
        for sub in [4, 8] {
            let cands: Vec<Candidate> = lp_reference::candidate_indices(&side, sub).iter().map(|&i| all[i as usize]).collect();
            let mut best = f64::INFINITY;
            let mut surf = up.clone();
            for _ in 0..5 { surf = up.clone(); let t = Instant::now(); lower_to_optimum(&mut surf, &cands, &s.trim, sub); best = best.min(t.elapsed().as_secs_f64() * 1e3); }
            let before = env.excess(&surf) / e_ref;
            let cert = certify_surface(&pts, &s.frame, &s.domain, &mut surf, Side::Upper).unwrap();
            println!("{name} sub {sub}: {} candidates, LP {best:.2} ms, before certify {before:.4}, after {:.4} (corrected {})", cands.len(), env.excess(&surf) / e_ref, cert.corrected_points);
        }
    }
}
