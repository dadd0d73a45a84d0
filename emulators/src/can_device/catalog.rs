//! Every emulated CAN model by name, the options they share and the world
//! they measure, so that a node can make any of them.

use super::ars408::{Ars408Emulator, RadarConfig};
use super::benewake::{BenewakeCanEmulator, BenewakeCanModel, UnitSpec};
use super::emulator::CanDeviceEmulator;
use shroud_drivers::assembly::MountPose;
use shroud_sim::{Bvh, MovingSpheres};
use std::sync::Arc;

/// The models [`can_emulator`] makes.
pub const CAN_MODELS: [&str; 5] = [
    "ars408",
    "tf03-can",
    "tfmini-i-can",
    "tf02-i-can",
    "tf02-can",
];

/// What the devices measure: moving spheres for the radar (objects with
/// velocities), a triangle mesh for the rangefinders' rays (none: nothing to
/// hit, every reading invalid).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CanWorld {
    pub spheres: MovingSpheres,
    pub mesh: Option<Arc<Bvh>>,
}

/// One Benewake rangefinder on the bus.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RangefinderSpec {
    /// The id it sends on (its receive id follows: see
    /// [`BenewakeCanModel::default_rx_id`]).
    pub id: u32,
    /// It sends extended (29-bit) frames.
    pub extended: bool,
    /// Where it sits in the mesh's frame; it measures along its +x.
    pub mount: MountPose,
}

/// Options every emulated CAN model takes (each uses what applies to it).
#[derive(Debug, Clone, PartialEq)]
pub struct CanEmulatorOptions {
    /// ARS408: ids + 0x10 · sensor_id (0..=7).
    pub sensor_id: u8,
    /// ARS408: where the radar sits in the scene (robot/world frame); it
    /// looks along its +x.
    pub radar_mount: MountPose,
    /// Benewake: the units on the bus; empty = one unit at the model's
    /// default id and format, at the origin looking along +x.
    pub rangefinders: Vec<RangefinderSpec>,
    /// Drop one frame in the middle of every n-th cycle (0 = never): the
    /// radar's middle 0x701 (0x60B), the rangefinders' middle unit's reading.
    pub drop_frame_every: u64,
    /// Seed of the measurement noise.
    pub seed: u64,
}

impl Default for CanEmulatorOptions {
    /// Sensor 0; the radar 10 m behind the default spheres' centre, 0.5 m
    /// up, looking at them (+x); one rangefinder of the model's default;
    /// nothing dropped; seed 0.
    fn default() -> Self {
        Self {
            sensor_id: 0,
            radar_mount: MountPose::from_xyz_rpy([-10.0, 0.0, 0.5], [0.0; 3]),
            rangefinders: Vec::new(),
            drop_frame_every: 0,
            seed: 0,
        }
    }
}

/// A fresh (just powered up) emulator of `model` measuring `world`.
pub fn can_emulator(
    model: &str,
    options: &CanEmulatorOptions,
    world: CanWorld,
) -> Result<Box<dyn CanDeviceEmulator>, String> {
    if model == "ars408" {
        let config = RadarConfig {
            sensor_id: options.sensor_id,
            ..RadarConfig::default()
        };
        return Ok(Box::new(Ars408Emulator::new(
            world.spheres,
            options.radar_mount,
            config,
            options.drop_frame_every,
            options.seed,
        )?));
    }
    if let Some(benewake) = BenewakeCanModel::from_name(model) {
        let units: Vec<UnitSpec> = if options.rangefinders.is_empty() {
            vec![UnitSpec {
                id: benewake.default_id(),
                extended: benewake.default_extended(),
                mount: MountPose::default(),
            }]
        } else {
            options
                .rangefinders
                .iter()
                .map(|r| UnitSpec {
                    id: r.id,
                    extended: r.extended,
                    mount: r.mount,
                })
                .collect()
        };
        return Ok(Box::new(BenewakeCanEmulator::new(
            benewake,
            &units,
            world.mesh,
            options.drop_frame_every,
            options.seed,
        )?));
    }
    Err(format!(
        "unknown CAN device model {model:?} (one of {})",
        CAN_MODELS.join(", ")
    ))
}
