//! Options of an emulated range sensor (`shroud sensor-sim --device` and the
//! `device-sim` node): the model, the world it measures, its mount, and the
//! faults it shows. A CAN device (ARS408, Benewake CAN) is emulated behind an
//! emulated SLCAN adapter, itself a serial device.

use super::can_device::RangefinderArg;
use super::mount::MountArgs;
use crate::ingest::EmulatorLine;
use anyhow::{bail, Context, Result};
use clap::Args;
use shroud_drivers::assembly::MountPose;
use shroud_emulators::can_device::{
    can_emulator, CanDeviceEmulator, CanEmulatorOptions, CanWorld, RangefinderSpec, CAN_MODELS,
};
use shroud_emulators::device::hokuyo::HokuyoModel;
use shroud_emulators::device::{EmulatorOptions, Faults, MeshRays, SerialDeviceEmulator, MODELS};
use shroud_emulators::SlcanAdapter;
use shroud_shapes::format::parse_triangle_mesh;
use shroud_sim::MovingSpheres;
use shroud_sim::{Bvh, TableTop, Terrain, DEFAULT_CYLINDER_SEGMENTS, DEFAULT_TERRAIN_CELLS};
use std::path::PathBuf;
use std::sync::Arc;

/// Makes a fresh emulator at each power-up.
pub type EmulatorMaker = Box<dyn FnMut() -> Result<Box<dyn SerialDeviceEmulator>> + Send>;

#[derive(Debug, Clone, Args)]
pub struct EmulatorArgs {
    /// What the emulated device measures: table-top, terrain, or a mesh file
    /// (OBJ, PLY or STL) in metres, robot frame.
    #[arg(long, default_value = "table-top")]
    pub world: String,
    #[command(flatten)]
    pub mount: MountArgs,
    /// Keep a symlink at this path pointing at the device's pty (a stable
    /// name across unplugs, like /dev/serial/by-id/...).
    #[arg(long)]
    pub link: Option<PathBuf>,
    /// Send a burst of random bytes before every n-th scan; 0 = never.
    #[arg(long, default_value_t = 0)]
    pub garbage_every: u64,
    /// Seconds after power-up until the device stops sending for --stall-for.
    #[arg(long)]
    pub stall_after: Option<f64>,
    #[arg(long, default_value_t = 2.0)]
    pub stall_for: f64,
    /// Seconds after start until the device is unplugged for --unplug-for
    /// (it comes back powered up afresh, behind the same --link).
    #[arg(long)]
    pub unplug_after: Option<f64>,
    #[arg(long, default_value_t = 2.0)]
    pub unplug_for: f64,
    /// Stop after this many seconds (default: run until interrupted).
    #[arg(long)]
    pub duration: Option<f64>,
    /// Emulate an RS-232 link whose UART starts at this baud rate (Hokuyo;
    /// default: USB, where the host's rate does not matter).
    #[arg(long)]
    pub rs232: Option<u32>,
    /// The Hokuyo starts in SCIP 1.1 (as older URG-04LX firmware does).
    #[arg(long)]
    pub scip1: bool,
    /// The device's millisecond clock at power-up (Hokuyo: test the 24-bit wrap).
    #[arg(long, default_value_t = 0)]
    pub clock_start_ms: u32,
    /// The device enters its abnormal state after this many scans (Hokuyo:
    /// it answers `0L` until rebooted by two RB commands).
    #[arg(long)]
    pub abnormal_after: Option<u64>,
    /// CAN devices: the ARS408's sensor ID (0..=7; its ids move by 0x10 per unit).
    #[arg(long, default_value_t = 0)]
    pub sensor_id: u8,
    /// CAN devices: a Benewake rangefinder on the bus, `NAME@ID:x,y,z,roll,pitch,yaw`
    /// (repeat for several; default one at the model's id, at the origin).
    #[arg(long = "rangefinder", allow_hyphen_values = true)]
    pub rangefinders: Vec<String>,
    /// CAN devices: leave one frame out of the middle of every n-th
    /// measurement cycle (0 = never), as a bus that loses frames does.
    #[arg(long, default_value_t = 0)]
    pub drop_frame_every: u64,
}

impl Default for EmulatorArgs {
    fn default() -> Self {
        Self {
            world: "table-top".into(),
            mount: MountArgs::default(),
            link: None,
            garbage_every: 0,
            stall_after: None,
            stall_for: 2.0,
            unplug_after: None,
            unplug_for: 2.0,
            duration: None,
            rs232: None,
            scip1: false,
            clock_start_ms: 0,
            abnormal_after: None,
            sensor_id: 0,
            rangefinders: Vec::new(),
            drop_frame_every: 0,
        }
    }
}

impl EmulatorArgs {
    /// Checks the options and loads the world, then returns a maker of fresh
    /// emulators of `model` (one per power-up).
    pub fn maker(&self, model: &str, corrupt_every: u64, seed: u64) -> Result<EmulatorMaker> {
        self.check_line()?;
        if CAN_MODELS.contains(&model) {
            if corrupt_every != 0 {
                bail!("--corrupt-every applies to the serial models; a CAN bus checks its own frames (use --drop-frame-every)");
            }
            let mut make = self.can_maker(model, seed)?;
            return Ok(Box::new(move || -> Result<Box<dyn SerialDeviceEmulator>> {
                let device = make()?;
                let bitrate = can_bitrate(device.model());
                Ok(Box::new(SlcanAdapter::new(device, bitrate)))
            })
                as Box<
                    dyn FnMut() -> Result<Box<dyn SerialDeviceEmulator>> + Send,
                >);
        }
        if !MODELS.contains(&model) {
            bail!(
                "unknown device model {model:?} (one of {}, {})",
                MODELS.join(", "),
                CAN_MODELS.join(", ")
            );
        }
        let can_only = [
            ("--sensor-id", self.sensor_id != 0),
            ("--rangefinder", !self.rangefinders.is_empty()),
            ("--drop-frame-every", self.drop_frame_every != 0),
        ];
        for (flag, given) in can_only {
            if given {
                bail!(
                    "{flag} applies to the CAN models ({}) only",
                    CAN_MODELS.join(", ")
                );
            }
        }
        let hokuyo_only = [
            ("--rs232", self.rs232.is_some()),
            ("--scip1", self.scip1),
            ("--clock-start-ms", self.clock_start_ms != 0),
            ("--abnormal-after", self.abnormal_after.is_some()),
        ];
        for (flag, given) in hokuyo_only {
            if given && HokuyoModel::from_name(model).is_none() {
                bail!("{flag} applies to the Hokuyo models (urg-04lx, utm-30lx) only");
            }
        }
        let bvh = Arc::new(self.world_bvh()?);
        let mount = self.mount.mount()?;
        let start_unix_ns = crate::transport::unix_ns();
        // Validate once, so that a bad mount is an error before the pty opens.
        MeshRays::new(bvh.clone(), mount.clone(), start_unix_ns).map_err(anyhow::Error::msg)?;
        let options = EmulatorOptions {
            faults: Faults {
                corrupt_every,
                garbage_every: self.garbage_every,
                seed,
            },
            seed,
            rs232_baud: self.rs232,
            starts_in_scip1: self.scip1,
            clock_start_ms: self.clock_start_ms,
            abnormal_after_scans: self.abnormal_after,
        };
        let model = model.to_owned();
        let mut power_ups = 0u64;
        Ok(Box::new(move || {
            power_ups += 1;
            // Each power-up measures the same world on the same wall clock.
            let rays = MeshRays::new(bvh.clone(), mount.clone(), crate::transport::unix_ns())
                .map_err(anyhow::Error::msg)?;
            let options = EmulatorOptions {
                seed: options.seed.wrapping_add(power_ups),
                ..options.clone()
            };
            shroud_emulators::device::emulator(&model, Box::new(rays), &options)
                .map_err(anyhow::Error::msg)
        }))
    }

    /// Checks the options and loads the world, then returns a maker of fresh
    /// CAN device emulators of `model` (one per power-up), without a transport.
    pub fn can_maker(
        &self,
        model: &str,
        seed: u64,
    ) -> Result<impl FnMut() -> Result<Box<dyn CanDeviceEmulator>> + Send> {
        let serial_only = [
            ("--rs232", self.rs232.is_some()),
            ("--scip1", self.scip1),
            ("--clock-start-ms", self.clock_start_ms != 0),
            ("--abnormal-after", self.abnormal_after.is_some()),
            ("--garbage-every", self.garbage_every != 0),
        ];
        for (flag, given) in serial_only {
            if given {
                bail!("{flag} applies to the serial models, not {model}");
            }
        }
        if self.mount.sweep.is_some() || self.mount.mount_joint.is_some() {
            bail!("an emulated CAN device sits on a fixed --mount");
        }
        let radar = model == "ars408";
        if radar && !self.rangefinders.is_empty() {
            bail!("--rangefinder applies to the Benewake CAN models, not the ARS408");
        }
        if !radar && self.sensor_id != 0 {
            bail!("--sensor-id applies to the ARS408, not {model}");
        }
        if !radar && self.mount.mount != "0,0,0,0,0,0" {
            bail!(
                "{model}: give each rangefinder's pose in --rangefinder NAME@ID:POSE, not --mount"
            );
        }
        let radar_mount: MountPose = self.mount.mount.parse().context("--mount")?;
        let rangefinders = self
            .rangefinders
            .iter()
            .map(|text| {
                let r: RangefinderArg = text.parse()?;
                Ok(RangefinderSpec {
                    id: r.id,
                    extended: model == "tf02-can",
                    mount: r.mount,
                })
            })
            .collect::<Result<Vec<_>>>()?;
        let options = CanEmulatorOptions {
            sensor_id: self.sensor_id,
            radar_mount,
            rangefinders,
            drop_frame_every: self.drop_frame_every,
            seed,
        };
        let world = CanWorld {
            spheres: MovingSpheres::default(),
            mesh: Some(Arc::new(self.world_bvh()?)),
        };
        // Validate once, so that bad options are an error before the pty opens.
        can_emulator(model, &options, world.clone()).map_err(anyhow::Error::msg)?;
        let model = model.to_owned();
        Ok(move || can_emulator(&model, &options, world.clone()).map_err(anyhow::Error::msg))
    }

    /// The line's times: finite and non-negative seconds.
    pub fn check_line(&self) -> Result<()> {
        for (name, value) in [
            ("--stall-for", self.stall_for),
            ("--unplug-for", self.unplug_for),
        ] {
            if !(value.is_finite() && value >= 0.0) {
                bail!("{name} must be a non-negative number of seconds, got {value}");
            }
        }
        for (name, value) in [
            ("--stall-after", self.stall_after),
            ("--unplug-after", self.unplug_after),
            ("--duration", self.duration),
        ] {
            if value.is_some_and(|v| !(v.is_finite() && v >= 0.0)) {
                bail!("{name} must be a non-negative number of seconds");
            }
        }
        Ok(())
    }

    /// Refuses the pseudo-terminal line's options, for an emulator that runs
    /// elsewhere (`--format candump`, `--format socketcan`).
    pub fn refuse_line_options(&self, format: &str) -> Result<()> {
        let line_only = [
            ("--link", self.link.is_some()),
            ("--stall-after", self.stall_after.is_some()),
            ("--unplug-after", self.unplug_after.is_some()),
        ];
        for (flag, given) in line_only {
            if given {
                bail!("{flag} applies to an emulator on a pseudo-terminal, not --format {format}");
            }
        }
        Ok(())
    }

    /// The line's schedule of faults and its link.
    pub fn line(&self) -> EmulatorLine {
        EmulatorLine {
            link: self.link.clone(),
            stall_after: self.stall_after,
            stall_for: self.stall_for,
            unplug_after: self.unplug_after,
            unplug_for: self.unplug_for,
            duration: self.duration,
        }
    }

    fn world_bvh(&self) -> Result<Bvh> {
        let mesh = match self.world.as_str() {
            "table-top" => TableTop::default().mesh(DEFAULT_CYLINDER_SEGMENTS)?,
            "terrain" => Terrain::default().mesh(DEFAULT_TERRAIN_CELLS)?,
            path => {
                let bytes = std::fs::read(path)
                    .with_context(|| format!("cannot read the world mesh {path}"))?;
                parse_triangle_mesh(&bytes).with_context(|| format!("world mesh {path}"))?
            }
        };
        Ok(Bvh::build(&mesh)?)
    }
}

/// The bus bitrate a CAN model runs at out of the box (ARS408: 500 kbit/s;
/// TF03-CAN and TF02: 1 Mbit/s; TFmini-i-CAN and TF02-i-CAN: 250 kbit/s;
/// `sensors.md` §2.1, §2.2): the emulated adapter's bus.
pub fn can_bitrate(model: &str) -> u32 {
    match model {
        "ars408" => 500_000,
        "tfmini-i-can" | "tf02-i-can" => 250_000,
        _ => 1_000_000,
    }
}
