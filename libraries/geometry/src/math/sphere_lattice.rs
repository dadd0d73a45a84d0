//! Nearly uniform directions on the unit sphere (the Fibonacci lattice): test
//! clouds and the paper experiments' spherical samples.

use glam::DVec3;

/// `n` unit vectors spread evenly over the sphere, from the +z pole down.
pub fn fibonacci_sphere(n: usize) -> Vec<DVec3> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..n)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
            let s = (1.0 - z * z).sqrt();
            let a = golden * i as f64;
            DVec3::new(s * a.cos(), s * a.sin(), z)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_vectors_balanced_about_the_centre() {
        let d = fibonacci_sphere(1000);
        assert!(d.iter().all(|v| (v.length() - 1.0).abs() < 1e-12));
        assert!((d.iter().sum::<DVec3>() / 1000.0).length() < 1e-2);
    }
}
