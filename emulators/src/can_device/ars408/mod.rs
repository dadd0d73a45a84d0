//! An emulated Continental ARS408-21 long-range radar on CAN (sensors.md
//! §2.2): RadarState, VersionID, cluster and object cycles measured from
//! moving spheres, and RadarConfiguration answered as the radar does. Every
//! frame goes through the builtin ARS408 DBC, the one the driver reads with.

mod config;
mod emulator;
pub(crate) mod frames;
pub(crate) mod scene;

pub use config::{OutputType, RadarConfig};
pub use emulator::{
    Ars408Counts, Ars408Emulator, BITRATE, CYCLE_PERIOD_S, SENSOR_ID_STEP, STATE_PERIOD_S,
    VERSION_PERIOD_S,
};
pub use frames::{MAX_CLUSTERS, MAX_OBJECTS, VERSION};
pub use scene::{
    HALF_AZIMUTH_DEG, HALF_ELEVATION_DEG, MOVING_SPEED_MPS, NEAR_RANGE_M, STATIC_CLUSTERS,
};
