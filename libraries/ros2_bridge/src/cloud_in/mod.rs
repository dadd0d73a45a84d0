//! A ROS 2 `PointCloud2` as a shroud cloud: read in its own field layout,
//! placed in the world by its sensor's mount, stamped with the header's time
//! (the device's word: ages are measured on the nodes' own clocks), and its
//! rays without a return stated as unseen, or refused when they cannot be.

mod camera_check;
mod layout;
mod mount;
mod read;

pub use layout::PointLayout;
pub use mount::{CloudMount, PinholeCamera};

use crate::{ns_of_time, CloudInError};
use read::{read_points, ReadPoints};
use shroud_geometry::cloud::{dark_cones, EmptyRays};
use shroud_msg::{CloudMessage, NoReturn};
use shroud_ros2::PointCloud2;

/// A cloud made from a `PointCloud2`, with what was left out.
#[derive(Debug, Clone, PartialEq)]
pub struct RosCloud {
    pub message: CloudMessage,
    /// Points without a return (not finite), stated as empty rays.
    pub empty_rays: usize,
    /// Intensities that were not finite, sent as 0.
    pub nonfinite_intensity: usize,
}

/// `cloud` as shroud's cloud number `sequence` from `source`.
///
/// Rays without a return must be stated, since a black object returns
/// nothing, like empty space: in an organised cloud (height above 1) from a
/// mount with a camera, they become the cloud's dark cones
/// (`shroud_geometry::cloud::dark_cones`) and the camera's rectangle its
/// field of view; anywhere else their directions are unknown and the cloud
/// is refused (a silent sensor halts the guard as stale, never clears it).
pub fn cloud_from_ros(
    cloud: &PointCloud2<'_>,
    mount: &CloudMount,
    source: &str,
    sequence: u64,
) -> Result<RosCloud, CloudInError> {
    mount.validate()?;
    let stamp = &cloud.header.stamp;
    let stamp_ns = ns_of_time(stamp).ok_or(CloudInError::Stamp {
        sec: stamp.sec,
        nanosec: stamp.nanosec,
    })?;
    let layout = PointLayout::of(cloud)?;
    let read = read_points(&layout, &cloud.data, mount);
    let no_return = stated_empty_rays(cloud, &layout, mount, &read)?;
    let mut message = CloudMessage::new(stamp_ns, sequence, source, mount.pose(), &read.points);
    if let Some(intensity) = &read.intensity {
        message = message.with_intensity(intensity);
    }
    message.field_of_view = mount.field_of_view();
    message.no_return = no_return;
    Ok(RosCloud {
        message,
        empty_rays: read.empty_count,
        nonfinite_intensity: read.nonfinite_intensity,
    })
}

fn stated_empty_rays(
    cloud: &PointCloud2<'_>,
    layout: &PointLayout,
    mount: &CloudMount,
    read: &ReadPoints,
) -> Result<Option<NoReturn>, CloudInError> {
    if read.empty_count == 0 {
        return Ok(None);
    }
    if layout.height <= 1 {
        return Err(CloudInError::UnplacedEmptyRays {
            count: read.empty_count,
        });
    }
    let Some(camera) = mount.camera else {
        return Err(CloudInError::EmptyRaysWithoutCamera {
            count: read.empty_count,
            height: cloud.height,
            width: cloud.width,
        });
    };
    let (rows, columns) = (layout.height, layout.width);
    // The returned points test the model; the cones widen by what they
    // measured, so a slightly miscalibrated camera still covers its rays.
    let spread = camera.ray_spread(rows, columns);
    let deviation = camera_check::model_deviation(layout, &cloud.data, &camera, spread)?;
    let rays = EmptyRays {
        rows,
        columns,
        empty: &read.empty,
    };
    let rotation = mount.rotation();
    let direction = |i: usize| rotation * camera.ray(rows, columns, i / columns, i % columns);
    Ok(dark_cones(
        mount.position,
        &rays,
        direction,
        spread + deviation,
    )?)
}

#[cfg(test)]
mod tests;
