//! What a simulated sensor measures along one ray: the first surface it
//! hits, and how well that surface reflects.

/// One return of a ray.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RayReturn {
    /// Metres along the ray.
    pub range: f64,
    /// How well the surface reflects, in [0, 1] (devices turn it into their
    /// own intensity or strength scale).
    pub reflectance: f64,
}

/// The world as a device sees it: the first surface along a ray of its scan
/// plane. Implementations place the sensor (a mount that may tilt or rotate
/// over time) and cast into a scene.
pub trait RaySource: Send {
    /// The return of the ray leaving the sensor at `angle` radians
    /// (counter-clockwise from the sensor's +x, in its scan plane, REP-103) at
    /// `time` seconds of emulator time, if a surface lies within `max_range`
    /// metres. No noise: the emulator adds its device's own.
    fn cast(&self, angle: f64, time: f64, max_range: f64) -> Option<RayReturn>;
}
