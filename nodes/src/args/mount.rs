//! Where a range sensor sits and how its scans become clouds: the options of
//! `shroud node serial` for real devices and of the emulators that must agree
//! with it (`shroud sensor-sim --device ...`).

use anyhow::{bail, Context, Result};
use clap::{Args, ValueEnum};
use glam::DVec3;
use shroud_drivers::assembly::{
    AssemblyConfig, CloudWindow, MountMotion, MountPose, MovingMount, SweepProfile,
    DEFAULT_MAX_POSITION_ERROR_M,
};

/// The turning axis of a moving mount, in the mount's base frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum MountAxis {
    /// Roll axis (forward).
    X,
    /// Pitch axis (left): a nodding (tilting) unit.
    Y,
    /// Yaw axis (up): a panning (rotating) unit.
    Z,
}

/// The sensor's mount in the robot's frame (REP-103: x forward, y left, z up).
#[derive(Debug, Clone, Args)]
pub struct MountArgs {
    /// The mount (the turning unit's base, if it moves) in the robot's frame:
    /// x,y,z in metres, roll,pitch,yaw in degrees.
    #[arg(long, default_value = "0,0,0,0,0,0", allow_hyphen_values = true)]
    pub mount: String,
    /// The turning unit's axis in the mount's frame.
    #[arg(long, value_enum, default_value_t = MountAxis::Y)]
    pub mount_axis: MountAxis,
    /// The sensor on the turning part: x,y,z (m), roll,pitch,yaw (degrees).
    #[arg(long, default_value = "0,0,0,0,0,0", allow_hyphen_values = true)]
    pub sensor_offset: String,
    /// The unit turns by this profile on the wall clock (phase locked to the
    /// Unix epoch): sine:AMPLITUDE_DEG:PERIOD_S[:CENTER_DEG],
    /// triangle:AMPLITUDE_DEG:PERIOD_S[:CENTER_DEG] or rotate:PERIOD_S.
    #[arg(long, conflicts_with = "mount_joint")]
    pub sweep: Option<String>,
    /// The unit's angle is this joint of the joint states on `joints/<--joints>`.
    #[arg(long)]
    pub mount_joint: Option<String>,
}

impl Default for MountArgs {
    /// A fixed mount at the robot's origin.
    fn default() -> Self {
        Self {
            mount: "0,0,0,0,0,0".into(),
            mount_axis: MountAxis::Y,
            sensor_offset: "0,0,0,0,0,0".into(),
            sweep: None,
            mount_joint: None,
        }
    }
}

impl MountArgs {
    /// The mount these options describe.
    pub fn mount(&self) -> Result<MovingMount> {
        let base: MountPose = self.mount.parse()?;
        let sensor: MountPose = self.sensor_offset.parse()?;
        let axis = match self.mount_axis {
            MountAxis::X => DVec3::X,
            MountAxis::Y => DVec3::Y,
            MountAxis::Z => DVec3::Z,
        };
        let motion = match (&self.sweep, &self.mount_joint) {
            (Some(profile), _) => MountMotion::Profile(profile.parse::<SweepProfile>()?),
            (None, Some(name)) if name.is_empty() => bail!("--mount-joint needs a joint name"),
            (None, Some(name)) => MountMotion::Joint { name: name.clone() },
            (None, None) => MountMotion::Fixed,
        };
        Ok(MovingMount {
            base,
            axis,
            sensor,
            motion,
        })
    }
}

/// How scans are gathered into clouds.
#[derive(Debug, Clone, Args)]
pub struct CloudArgs {
    #[command(flatten)]
    pub mount: MountArgs,
    /// One cloud per `sweep` of a moving mount, per `scans:N`, or per
    /// `time:SECONDS` (default: sweep for a moving mount, else scans:1).
    #[arg(long)]
    pub cloud: Option<String>,
    /// Joint-state topic name (`joints/<name>`) carrying --mount-joint.
    #[arg(long, default_value = "mount")]
    pub joints: String,
    /// Points a cloud may hold before it is published early.
    #[arg(long, default_value_t = 2_000_000)]
    pub max_cloud_points: usize,
    /// The largest position error (metres) a placed reading may have. A
    /// reading of a device that sends no time (a Benewake) is placed at the
    /// best estimate of when it was measured; the uncertainty of that time,
    /// through the mount's motion, bounds how far the point can be from
    /// where it was measured. Readings with a larger bound are dropped
    /// (counted as `readings_late_beyond_bound`), as are those whose time
    /// has no bound (`readings_late_unbounded`). Each cloud states the
    /// largest bound of its points (`position_error_m`).
    #[arg(long, default_value_t = DEFAULT_MAX_POSITION_ERROR_M)]
    pub max_position_error: f64,
}

impl CloudArgs {
    /// The assembly these options describe.
    pub fn assembly(&self) -> Result<AssemblyConfig> {
        let mount = self.mount.mount().context("sensor mount")?;
        let window = match &self.cloud {
            Some(text) => text.parse::<CloudWindow>()?,
            None if mount.sweeps() => CloudWindow::Sweep,
            None => CloudWindow::Scans(1),
        };
        Ok(AssemblyConfig {
            window,
            max_points: self.max_cloud_points,
            max_position_error_m: self.max_position_error,
            ..AssemblyConfig::fixed(mount)
        })
    }
}
