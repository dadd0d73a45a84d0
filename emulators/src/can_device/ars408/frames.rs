//! The ARS408-21's frames, encoded through the builtin DBC
//! (`shroud_drivers::dbc::builtin("ars408")`): RadarState, VersionID,
//! and the cluster and object cycles (sensors.md §2.2).

use super::config::RadarConfig;
use super::scene::{Detection, Target, NEAR_RANGE_M};
use crate::can_device::signals::encode;
use shroud_drivers::can::CanFrame;
use shroud_drivers::dbc::{CanDatabase, DbcError};

/// Clusters per cycle at most: IDs are 8 bits, and the two 8-bit counts of
/// 0x600 sum to at most this in practice (the radar reports up to 250).
pub const MAX_CLUSTERS: usize = 250;
/// Objects per cycle at most (0x60A NofObjects; the radar tracks up to 100).
pub const MAX_OBJECTS: usize = 100;
/// VersionID the emulator reports: major, minor, patch.
pub const VERSION: [u8; 3] = [4, 33, 0];
/// 0x600 / 0x60A InterfaceVersion the emulator reports.
const INTERFACE_VERSION: f64 = 0.0;

/// Quality codes the emulator reports for every cluster and object: indexes
/// into the radar's rms tables (0x5 ≈ 0.1 m, 0.1 m/s in Continental's
/// table), PdH0 1 (false-alarm probability below 25 %), AmbigState 4
/// (unambiguous), InvalidState 0 (valid), ProbOfExist 7 (≥ 99.9 %).
const RMS_CODE: f64 = 5.0;
const PDH0: f64 = 1.0;
const AMBIG_UNAMBIGUOUS: f64 = 4.0;
const INVALID_STATE_VALID: f64 = 0.0;
const PROB_OF_EXIST: f64 = 7.0;
/// MeasState: 1 new object, 2 measured.
const MEAS_STATE_NEW: f64 = 1.0;
const MEAS_STATE_MEASURED: f64 = 2.0;
/// Obj_3_Extended Class the emulator gives every sphere: 0, point.
const CLASS_POINT: f64 = 0.0;

/// DynProp: 0 moving, 1 stationary.
fn dyn_prop(moving: bool) -> f64 {
    if moving {
        0.0
    } else {
        1.0
    }
}

/// 0x201 RadarState reflecting `config`; no error bits; NVM read succeeded
/// at power-up; motion input reported as received (the emulator models no
/// ego motion, so none is missing).
pub(crate) fn radar_state(db: &CanDatabase, config: &RadarConfig) -> Result<CanFrame, DbcError> {
    let flag = |b: bool| f64::from(u8::from(b));
    encode(
        db,
        "RadarState",
        &[
            ("NVMwriteStatus", flag(config.stored)),
            ("NVMReadStatus", 1.0),
            ("MaxDistanceCfg", config.max_distance_m),
            ("PersistentError", 0.0),
            ("InterferenceError", 0.0),
            ("TemperatureError", 0.0),
            ("TemporaryError", 0.0),
            ("VoltageError", 0.0),
            ("RadarPowerCfg", f64::from(config.radar_power)),
            ("SensorID", f64::from(config.sensor_id)),
            ("SortIndex", f64::from(config.sort_index)),
            ("OutputTypeCfg", config.output.code()),
            ("SendQualityCfg", flag(config.send_quality)),
            ("SendExtInfoCfg", flag(config.send_ext_info)),
            ("MotionRxState", 0.0),
            ("RCS_Threshold", f64::from(config.rcs_threshold)),
        ],
    )
}

/// 0x700 VersionID: [`VERSION`], standard range, country code 0.
pub(crate) fn version(db: &CanDatabase) -> Result<CanFrame, DbcError> {
    let [major, minor, patch] = VERSION.map(f64::from);
    encode(
        db,
        "VersionID",
        &[
            ("MajorRelease", major),
            ("MinorRelease", minor),
            ("PatchLevel", patch),
            ("ExtendedRange", 0.0),
            ("CountryCode", 0.0),
        ],
    )
}

/// A cluster cycle: 0x600, then one 0x701 per cluster (IDs 0.. in order,
/// near clusters first, each group by range), then one 0x702 each when
/// quality is on. `drop_one`: leave the middle 0x701 out (0x600 still counts
/// it), as a lost frame would.
pub(crate) fn cluster_cycle(
    db: &CanDatabase,
    config: &RadarConfig,
    counter: u16,
    clusters: &[Detection],
    drop_one: bool,
) -> Result<Vec<CanFrame>, DbcError> {
    let mut sorted: Vec<Detection> = clusters.to_vec();
    sorted.sort_by(|a, b| {
        let is_far = |d: &Detection| d.range() > NEAR_RANGE_M;
        is_far(a)
            .cmp(&is_far(b))
            .then(a.range().total_cmp(&b.range()))
    });
    sorted.truncate(MAX_CLUSTERS);
    let near = sorted.iter().filter(|d| d.range() <= NEAR_RANGE_M).count();
    let far = sorted.len() - near;
    let mut frames = Vec::with_capacity(1 + 2 * sorted.len());
    frames.push(encode(
        db,
        "Cluster_0_Status",
        &[
            ("NofClustersNear", near as f64),
            ("NofClustersFar", far as f64),
            ("MeasCounter", f64::from(counter)),
            ("InterfaceVersion", INTERFACE_VERSION),
        ],
    )?);
    let dropped = drop_one.then_some(sorted.len() / 2);
    for (id, d) in sorted.iter().enumerate() {
        if Some(id) == dropped {
            continue;
        }
        frames.push(encode(
            db,
            "Cluster_1_General",
            &[
                ("ID", id as f64),
                ("DistLong", d.long),
                ("DistLat", d.lat),
                ("VrelLong", d.vlong),
                ("VrelLat", d.vlat),
                ("DynProp", dyn_prop(d.moving)),
                ("RCS", d.rcs),
            ],
        )?);
    }
    if config.send_quality {
        for id in 0..sorted.len() {
            frames.push(encode(
                db,
                "Cluster_2_Quality",
                &[
                    ("ID", id as f64),
                    ("DistLong_rms", RMS_CODE),
                    ("DistLat_rms", RMS_CODE),
                    ("VrelLong_rms", RMS_CODE),
                    ("VrelLat_rms", RMS_CODE),
                    ("Pdh0", PDH0),
                    ("AmbigState", AMBIG_UNAMBIGUOUS),
                    ("InvalidState", INVALID_STATE_VALID),
                ],
            )?);
        }
    }
    Ok(frames)
}

/// One tracked object as the radar reports it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Object {
    pub target: Target,
    /// Measured (noisy) position and velocity, radar frame.
    pub long: f64,
    pub lat: f64,
    pub vlong: f64,
    pub vlat: f64,
    /// First cycle the object appears in.
    pub new: bool,
}

impl Object {
    fn range(&self) -> f64 {
        self.long.hypot(self.lat)
    }

    /// Heading of the velocity in the radar's x-y plane, degrees; 0 when
    /// stationary.
    fn orientation_deg(&self) -> f64 {
        if self.target.moving() {
            self.vlat.atan2(self.vlong).to_degrees()
        } else {
            0.0
        }
    }
}

/// An object cycle: 0x60A, then one 0x60B per object, 0x60C each when
/// quality is on, 0x60D each when extended information is on; objects in
/// SortIndex order (0 as tracked, 1 by range, 2 by RCS, largest first).
/// `drop_one`: leave the middle 0x60B out.
pub(crate) fn object_cycle(
    db: &CanDatabase,
    config: &RadarConfig,
    counter: u16,
    objects: &[Object],
    drop_one: bool,
) -> Result<Vec<CanFrame>, DbcError> {
    let mut sorted: Vec<Object> = objects.to_vec();
    match config.sort_index {
        1 => sorted.sort_by(|a, b| a.range().total_cmp(&b.range())),
        2 => sorted.sort_by(|a, b| b.target.rcs().total_cmp(&a.target.rcs())),
        _ => {}
    }
    sorted.truncate(MAX_OBJECTS);
    let mut frames = Vec::with_capacity(1 + 3 * sorted.len());
    frames.push(encode(
        db,
        "Obj_0_Status",
        &[
            ("NofObjects", sorted.len() as f64),
            ("MeasCounter", f64::from(counter)),
            ("InterfaceVersion", INTERFACE_VERSION),
        ],
    )?);
    let dropped = drop_one.then_some(sorted.len() / 2);
    for (k, o) in sorted.iter().enumerate() {
        if Some(k) == dropped {
            continue;
        }
        frames.push(encode(
            db,
            "Obj_1_General",
            &[
                ("ID", o.target.index as f64),
                ("DistLong", o.long),
                ("DistLat", o.lat),
                ("VrelLong", o.vlong),
                ("VrelLat", o.vlat),
                ("DynProp", dyn_prop(o.target.moving())),
                ("RCS", o.target.rcs()),
            ],
        )?);
    }
    if config.send_quality {
        for o in &sorted {
            let state = if o.new {
                MEAS_STATE_NEW
            } else {
                MEAS_STATE_MEASURED
            };
            frames.push(encode(
                db,
                "Obj_2_Quality",
                &[
                    ("ID", o.target.index as f64),
                    ("DistLong_rms", RMS_CODE),
                    ("DistLat_rms", RMS_CODE),
                    ("VrelLong_rms", RMS_CODE),
                    ("VrelLat_rms", RMS_CODE),
                    ("ArelLong_rms", RMS_CODE),
                    ("ArelLat_rms", RMS_CODE),
                    ("Orientation_rms", RMS_CODE),
                    ("MeasState", state),
                    ("ProbOfExist", PROB_OF_EXIST),
                ],
            )?);
        }
    }
    if config.send_ext_info {
        for o in &sorted {
            frames.push(encode(
                db,
                "Obj_3_Extended",
                &[
                    ("ID", o.target.index as f64),
                    ("ArelLong", o.target.acceleration.x),
                    ("ArelLat", o.target.acceleration.y),
                    ("Class", CLASS_POINT),
                    ("OrientationAngle", o.orientation_deg()),
                    ("Length", 2.0 * o.target.radius),
                    ("Width", 2.0 * o.target.radius),
                ],
            )?);
        }
    }
    Ok(frames)
}
