//! A person crossing a robot cell, the scene of the speed and separation
//! monitoring demo: a vertical capsule (the ISO 13855 walking speed, 1.6 m/s,
//! by default) walks along a straight line across a floor, waits outside,
//! and walks back.

use crate::error::{check_finite, check_non_negative, check_points, check_positive, SceneError};
use crate::moving_spheres::Floor;
use crate::sampling::{on_sphere, stream_rng, time_key};
use rand::Rng;
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

/// Stream tag separating this scene's random numbers from the other scenes'.
const STREAM_TAG: u64 = 0x5045_5253_4f4e_2121; // "PERSON!!"

/// A person walking to and fro between `from` and `to` on the floor.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Crossing {
    /// Points on the person's surface (the floor's come after them).
    pub points: usize,
    /// The person's capsule: radius and height above the floor.
    pub radius: f32,
    pub height: f32,
    /// Where the walk starts and ends, `[x, y]` on the floor.
    pub from: [f32; 2],
    pub to: [f32; 2],
    /// Walking speed (m/s).
    pub speed: f32,
    /// Seconds spent standing at each end before walking back.
    pub pause_s: f32,
    pub seed: u64,
    /// The floor the person walks on, sampled too when given (its height is
    /// the capsule's foot either way; none: z = 0).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub floor: Option<Floor>,
}

impl Default for Crossing {
    /// A person 1.75 m tall walking at 1.6 m/s across a 6 m wide cell,
    /// 0.9 m from its centre line, resting 3 s outside each way.
    fn default() -> Self {
        Self {
            points: 6_000,
            radius: 0.25,
            height: 1.75,
            from: [-3.0, 0.9],
            to: [3.0, 0.9],
            speed: 1.6,
            pause_s: 3.0,
            seed: 0,
            floor: Some(Floor {
                z: 0.0,
                half_extent: 2.0,
                spacing: 0.04,
            }),
        }
    }
}

impl Crossing {
    pub fn validate(&self) -> Result<(), SceneError> {
        check_points("points", self.points)?;
        check_positive("radius", f64::from(self.radius))?;
        // NaN fails too.
        if self.height.partial_cmp(&(2.0 * self.radius)) != Some(std::cmp::Ordering::Greater) {
            return Err(SceneError::Degenerate {
                parameter: "height".into(),
                reason: "must exceed twice the radius",
            });
        }
        for (name, v) in [("from", self.from), ("to", self.to)] {
            check_finite(name, f64::from(v[0]))?;
            check_finite(name, f64::from(v[1]))?;
        }
        check_positive("speed", f64::from(self.speed))?;
        check_non_negative("pause_s", f64::from(self.pause_s))?;
        self.floor.as_ref().map_or(Ok(()), Floor::validate)
    }

    /// Points of every cloud: the person's and the floor's.
    pub fn total_points(&self) -> usize {
        let n = self.floor.as_ref().map_or(0, Floor::per_side);
        self.points + n * n
    }

    fn walk_s(&self) -> f64 {
        let d = [self.to[0] - self.from[0], self.to[1] - self.from[1]];
        f64::from(d[0].hypot(d[1])) / f64::from(self.speed)
    }

    /// Where the person stands at `time` seconds, `[x, y]`: walking from
    /// `from` to `to`, resting, walking back, resting, and again.
    pub fn position(&self, time: f64) -> [f64; 2] {
        let (walk, pause) = (self.walk_s(), f64::from(self.pause_s));
        let cycle = 2.0 * (walk + pause);
        let t = if cycle > 0.0 {
            time.rem_euclid(cycle)
        } else {
            0.0
        };
        let along = if t < walk {
            t / walk
        } else if t < walk + pause {
            1.0
        } else if t < 2.0 * walk + pause {
            1.0 - (t - walk - pause) / walk
        } else {
            0.0
        };
        let lerp = |a: f32, b: f32| f64::from(a) + along * f64::from(b - a);
        [
            lerp(self.from[0], self.to[0]),
            lerp(self.from[1], self.to[1]),
        ]
    }

    /// The person's capsule axis at `time`: foot and head centres.
    pub fn axis(&self, time: f64) -> [[f64; 3]; 2] {
        let [x, y] = self.position(time);
        let z = self.floor.as_ref().map_or(0.0, |f| f64::from(f.z));
        let r = f64::from(self.radius);
        [[x, y, z + r], [x, y, z + f64::from(self.height) - r]]
    }

    /// The cloud at `time`: points on the person's surface (its side and its
    /// two end caps, by area), then the floor. Deterministic in (config, time).
    pub fn generate(&self, time: f64) -> Result<Vec<[f32; 3]>, SceneError> {
        self.validate()?;
        check_finite("time", time)?;
        let [foot, head] = self.axis(time);
        let r = f64::from(self.radius);
        let side = TAU * r * (head[2] - foot[2]);
        let caps = 4.0 * std::f64::consts::PI * r * r;
        let mut rng = stream_rng(self.seed, &[STREAM_TAG, time_key(time)]);
        let mut cloud = Vec::with_capacity(self.points);
        for _ in 0..self.points {
            if rng.random::<f64>() * (side + caps) < side {
                let angle = rng.random::<f64>() * TAU;
                let z = foot[2] + rng.random::<f64>() * (head[2] - foot[2]);
                cloud.push([
                    (foot[0] + r * angle.cos()) as f32,
                    (foot[1] + r * angle.sin()) as f32,
                    z as f32,
                ]);
            } else {
                // A point of the sphere around the nearer end cap's centre,
                // kept on the cap's outer half.
                let p = on_sphere(&mut rng, head, r);
                let cap = if f64::from(p[2]) >= head[2] {
                    p
                } else {
                    let below = head[2] - f64::from(p[2]);
                    [p[0], p[1], (foot[2] - below) as f32]
                };
                cloud.push(cap);
            }
        }
        if let Some(floor) = &self.floor {
            cloud.extend(floor.points());
        }
        Ok(cloud)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_person_walks_across_rests_and_comes_back() {
        let c = Crossing::default();
        let walk = 6.0 / 1.6;
        let near = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).abs() + (p[1] - q[1]).abs() < 1e-6;
        assert!(near(c.position(0.0), [-3.0, 0.9]));
        let mid = c.position(walk / 2.0);
        assert!(mid[0].abs() < 1e-6, "{mid:?}");
        assert!(near(c.position(walk + 1.0), [3.0, 0.9]));
        let back = c.position(walk + 3.0 + walk / 2.0);
        assert!(back[0].abs() < 1e-6, "{back:?}");
        // Speed: 1.6 m/s while walking.
        let (a, b) = (c.position(1.0), c.position(1.1));
        assert!(((b[0] - a[0]) / 0.1 - 1.6).abs() < 1e-6);
    }

    #[test]
    fn every_person_point_is_on_the_capsule_and_the_floor_follows() {
        let c = Crossing::default();
        let cloud = c.generate(2.0).unwrap();
        let [foot, head] = c.axis(2.0);
        for p in &cloud[..c.points] {
            let p = [f64::from(p[0]), f64::from(p[1]), f64::from(p[2])];
            let z = p[2].clamp(foot[2], head[2]);
            let d =
                ((p[0] - foot[0]).powi(2) + (p[1] - foot[1]).powi(2) + (p[2] - z).powi(2)).sqrt();
            assert!((d - 0.25).abs() < 1e-5, "{p:?} at {d}");
        }
        assert!(cloud[c.points..].iter().all(|p| p[2] == 0.0));
        assert_eq!(cloud.len(), c.total_points());
        assert_eq!(cloud, c.generate(2.0).unwrap());
    }

    #[test]
    fn bad_settings_are_named() {
        let bad = |f: fn(&mut Crossing)| {
            let mut c = Crossing::default();
            f(&mut c);
            c.validate().unwrap_err().to_string()
        };
        assert!(bad(|c| c.speed = 0.0).contains("speed"));
        assert!(bad(|c| c.height = 0.4).contains("height"));
        assert!(bad(|c| c.from[0] = f32::NAN).contains("from"));
        assert!(bad(|c| c.pause_s = -1.0).contains("pause_s"));
    }
}
