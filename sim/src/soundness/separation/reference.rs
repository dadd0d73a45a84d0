//! A random trajectory for the simulated arm: waypoints joined by eased
//! (cosine) or constant-speed moves, with short dwells, whose nominal joint
//! speeds never exceed the velocity limits (so that at scale 1 the arm keeps
//! the limits the guard's bound assumes). Time along it is the arm's
//! progress: it advances at the applied speed scale.

use rand::Rng;
use std::f64::consts::FRAC_PI_2;

/// One move from `from` to `to` in `duration` seconds.
#[derive(Debug, Clone, PartialEq)]
pub struct Move {
    pub from: Vec<f64>,
    pub to: Vec<f64>,
    pub duration: f64,
    /// Cosine easing (zero speed at both ends, peak `π/2` times the mean);
    /// else constant speed.
    pub eased: bool,
}

/// The moves of a trajectory, back to back from nominal time 0.
#[derive(Debug, Clone, PartialEq)]
pub struct Reference {
    pub moves: Vec<Move>,
    starts: Vec<f64>,
}

impl Reference {
    /// Moves through waypoints (`waypoint` gives the next after the one it
    /// is passed, or the first when passed `None`) until the nominal time
    /// reaches `length`: each move at a random fraction (0.5 to 1, 1 in a
    /// third of them) of the speed that brings its fastest joint to its
    /// limit, eased or not, a tenth of them a dwell of 0.05 to 0.3 s.
    pub fn draw<R: Rng>(
        rng: &mut R,
        max_velocity: &[f64],
        length: f64,
        mut waypoint: impl FnMut(&mut R, Option<&[f64]>) -> Vec<f64>,
    ) -> Self {
        let mut moves = Vec::new();
        let mut at = waypoint(rng, None);
        let mut total = 0.0;
        while total < length {
            if rng.random_bool(0.1) {
                let duration = rng.random_range(0.05..0.3);
                moves.push(Move {
                    from: at.clone(),
                    to: at.clone(),
                    duration,
                    eased: false,
                });
                total += duration;
                continue;
            }
            let to = waypoint(rng, Some(&at));
            let eased = rng.random_bool(0.7);
            let fraction = if rng.random_bool(1.0 / 3.0) {
                1.0
            } else {
                rng.random_range(0.5..1.0)
            };
            let peak = if eased { FRAC_PI_2 } else { 1.0 };
            let duration = at
                .iter()
                .zip(&to)
                .zip(max_velocity)
                .map(|((a, b), v)| peak * (b - a).abs() / (fraction * v))
                .fold(0.0, f64::max);
            if duration <= 1e-6 {
                continue;
            }
            moves.push(Move {
                from: at,
                to: to.clone(),
                duration,
                eased,
            });
            total += duration;
            at = to;
        }
        Self::new(moves)
    }

    pub fn new(moves: Vec<Move>) -> Self {
        let mut starts = Vec::with_capacity(moves.len());
        let mut t = 0.0;
        for m in &moves {
            starts.push(t);
            t += m.duration;
        }
        Self { moves, starts }
    }

    /// Nominal length (s).
    pub fn length(&self) -> f64 {
        self.moves.last().map_or(0.0, |m| {
            self.starts.last().copied().unwrap_or(0.0) + m.duration
        })
    }

    /// The first waypoint.
    pub fn start(&self) -> &[f64] {
        self.moves.first().map_or(&[], |m| m.from.as_slice())
    }

    /// Positions and nominal velocities (per nominal second) at nominal time
    /// `tau`; after the end, the last waypoint at rest.
    pub fn at(&self, tau: f64, q: &mut [f64], dq: &mut [f64]) {
        let k = self.starts.partition_point(|&s| s <= tau).saturating_sub(1);
        let Some(m) = self.moves.get(k) else {
            return;
        };
        let u = ((tau - self.starts[k]) / m.duration).clamp(0.0, 1.0);
        let ended = tau >= self.starts[k] + m.duration;
        for (j, (a, b)) in m.from.iter().zip(&m.to).enumerate() {
            let delta = b - a;
            let (s, ds) = if m.eased {
                let phase = std::f64::consts::PI * u;
                (
                    0.5 * (1.0 - phase.cos()),
                    FRAC_PI_2 * phase.sin() / m.duration,
                )
            } else {
                (u, 1.0 / m.duration)
            };
            q[j] = a + delta * s;
            dq[j] = if ended { 0.0 } else { delta * ds };
        }
    }

    /// The fastest nominal speed of each joint (for the checks).
    pub fn peak_speeds(&self, dof: usize) -> Vec<f64> {
        let mut peak = vec![0.0f64; dof];
        for m in &self.moves {
            let factor = if m.eased { FRAC_PI_2 } else { 1.0 } / m.duration;
            for (j, (a, b)) in m.from.iter().zip(&m.to).enumerate() {
                peak[j] = peak[j].max((b - a).abs() * factor);
            }
        }
        peak
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn nominal_speeds_keep_the_limits_and_positions_are_continuous() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(5);
        let limits = [0.5, 1.0, 2.0];
        let r = Reference::draw(&mut rng, &limits, 5.0, |rng, _| {
            (0..3).map(|_| rng.random_range(-1.0..1.0)).collect()
        });
        assert!(r.length() >= 5.0);
        for (peak, limit) in r.peak_speeds(3).iter().zip(&limits) {
            assert!(*peak <= limit * (1.0 + 1e-12), "{peak} > {limit}");
        }
        // Finite differences stay within the limits and match the velocity.
        let (mut q0, mut q1, mut dq) = (vec![0.0; 3], vec![0.0; 3], vec![0.0; 3]);
        let h = 1e-5;
        let mut tau = 0.0;
        while tau < r.length() {
            r.at(tau, &mut q0, &mut dq);
            r.at(tau + h, &mut q1, &mut [0.0; 3]);
            for j in 0..3 {
                let fd = (q1[j] - q0[j]) / h;
                assert!(fd.abs() <= limits[j] * (1.0 + 1e-6), "{tau} {j}: {fd}");
                assert!(dq[j].abs() <= limits[j] * (1.0 + 1e-9));
            }
            tau += 0.013;
        }
        r.at(r.length() + 1.0, &mut q0, &mut dq);
        assert_eq!(dq, vec![0.0; 3]);
    }
}
