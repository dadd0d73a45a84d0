//! How ROS 2 clouds are placed in shroud's world (the `ros2` node and
//! `shroud replay` of a rosbag2 recording): the cloud frame's mount and,
//! for a depth camera's organised clouds, its field of view.

use anyhow::{Context, Result};
use clap::Args;
use shroud_ros2_bridge::{CloudMount, PinholeCamera};

#[derive(Debug, Clone, Args)]
pub struct RosCloudArgs {
    /// The ROS cloud frame's pose in shroud's world: `x,y,z,qx,qy,qz,qw`
    /// (metres, unit quaternion), a sensor's static extrinsics.
    #[arg(
        long,
        value_name = "X,Y,Z,QX,QY,QZ,QW",
        default_value = "0,0,0,0,0,0,1"
    )]
    pub cloud_mount: String,
    /// A depth camera's full horizontal and vertical fields of view in
    /// degrees, `H,V`: its organised clouds' rays without a return are then
    /// stated as unseen (without it such clouds are refused).
    #[arg(long, value_name = "H,V")]
    pub camera_fov: Option<String>,
    /// The camera's range, metres (the far end of its field of view).
    #[arg(long, default_value_t = 10.0)]
    pub camera_range: f64,
}

/// `N` comma-separated numbers of option `option`.
fn numbers<const N: usize>(text: &str, option: &str) -> Result<[f64; N]> {
    let values: Vec<f64> = text
        .split(',')
        .map(|v| v.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .with_context(|| format!("{option} {text:?}: not numbers"))?;
    values
        .try_into()
        .map_err(|v: Vec<f64>| anyhow::anyhow!("{option} {text:?}: {} numbers, not {N}", v.len()))
}

impl RosCloudArgs {
    /// The mount these options describe, checked.
    pub fn mount(&self) -> Result<CloudMount> {
        let [x, y, z, qx, qy, qz, qw] = numbers::<7>(&self.cloud_mount, "--cloud-mount")?;
        let camera = match &self.camera_fov {
            Some(text) => {
                let [h, v] = numbers::<2>(text, "--camera-fov")?;
                Some(PinholeCamera {
                    horizontal_fov: h.to_radians(),
                    vertical_fov: v.to_radians(),
                    max_range: self.camera_range,
                })
            }
            None => None,
        };
        let mount = CloudMount {
            position: [x, y, z],
            orientation: [qx, qy, qz, qw],
            camera,
        };
        mount.validate()?;
        Ok(mount)
    }
}
