//! Memory of a safe fit (paper 000's Table 1 clouds): the peak heap a default
//! 20 x 20 fit allocates above its input, as a ratio to the cloud's own size
//! (12 bytes a point), counted by this example's counting global allocator
//! (the `shroud` binary does not install it).
//!
//! `cargo run --release -p shroud-surrogate --example fit_memory`

use shroud_graph::metrics::{is_counting, live_bytes, peak_bytes, reset_peak, CountingAllocator};
use shroud_surrogate::{FitOptions, SurrogateFitter};

#[global_allocator]
static ALLOCATOR: CountingAllocator = CountingAllocator;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    println!("| N | cloud (MB) | extra heap of a fit (MB) | extra memory / cloud |");
    println!("|---:|---:|---:|---:|");
    for n in [10_000, 30_000, 50_000, 100_000, 300_000] {
        let points = shroud_sim::MovingSpheres {
            points: n,
            ..Default::default()
        }
        .generate(0.3)?;
        let mut fitter = SurrogateFitter::new(FitOptions::default())?;
        let mut extra = 0;
        // The first fit sizes the fitter's reusable buffers; the worst counts.
        for _ in 0..3 {
            let base = live_bytes();
            reset_peak();
            let fit = fitter.fit(&points)?;
            extra = extra.max(peak_bytes().saturating_sub(base));
            drop(fit);
        }
        let cloud = (n * 12) as f64;
        println!(
            "| {}K | {:.2} | {:.2} | {:.2} |",
            n / 1000,
            cloud / 1e6,
            extra as f64 / 1e6,
            extra as f64 / cloud
        );
    }
    assert!(is_counting(), "the counting allocator is installed");
    Ok(())
}
