//! A `PointCloud2`'s points read through its layout and placed in the world
//! by the mount: a point whose x, y or z is not finite is a ray without a
//! return (REP 117: NaN for no return, +/-Inf where a driver says so), kept
//! as a flag on the image grid instead of a point.

use super::layout::PointLayout;
use super::mount::CloudMount;

/// The returned points, in the world, and where the rays without one are.
#[derive(Debug, Default, Clone, PartialEq)]
pub struct ReadPoints {
    pub points: Vec<[f32; 3]>,
    /// One per point when the cloud has an `intensity` field; a value that
    /// is not finite is stored as 0 and counted in `nonfinite_intensity`.
    pub intensity: Option<Vec<f32>>,
    pub nonfinite_intensity: usize,
    /// Row-major flags over the cloud's `height x width`, `true` where the
    /// point has no return; empty when every point returned.
    pub empty: Vec<bool>,
    pub empty_count: usize,
}

/// Reads every point of `data` (whose length the layout checked).
pub fn read_points(layout: &PointLayout, data: &[u8], mount: &CloudMount) -> ReadPoints {
    let mut out = ReadPoints {
        points: Vec::with_capacity(layout.len()),
        intensity: layout.intensity.map(|_| Vec::with_capacity(layout.len())),
        ..ReadPoints::default()
    };
    let place = mount.placement();
    for row in 0..layout.height {
        for column in 0..layout.width {
            let point = layout.point(data, row, column);
            let local = layout.xyz(point);
            let world = place(local).as_vec3();
            if !world.is_finite() {
                out.mark_empty(layout, row, column);
                continue;
            }
            out.points.push(world.to_array());
            if let (Some(field), Some(values)) = (layout.intensity, out.intensity.as_mut()) {
                let value = field.read(point, layout.big_endian) as f32;
                out.nonfinite_intensity += usize::from(!value.is_finite());
                values.push(if value.is_finite() { value } else { 0.0 });
            }
        }
    }
    out
}

impl ReadPoints {
    fn mark_empty(&mut self, layout: &PointLayout, row: usize, column: usize) {
        if self.empty.is_empty() {
            self.empty = vec![false; layout.len()];
        }
        self.empty[row * layout.width + column] = true;
        self.empty_count += 1;
    }
}
