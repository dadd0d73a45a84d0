//! The messages and signals of the radar's DBC that the driver reads and
//! writes, looked up by name once, so that a user's DBC variant that lacks
//! one fails at start with a named error instead of mid-stream.

use super::config::RadarOutput;
use super::error::Ars408Error;
use crate::can::CanFrame;
use crate::dbc::{CanDatabase, DbcError, MessageSpec};

/// One message with the positions of the signals the driver uses, in the
/// order of the `NAMES` list it was bound with.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Bound<const N: usize> {
    pub spec: MessageSpec,
    index: [usize; N],
}

impl<const N: usize> Bound<N> {
    fn new(db: &CanDatabase, message: &str, names: [&str; N]) -> Result<Self, Ars408Error> {
        let spec = db
            .message(message)
            .filter(|m| !m.extended)
            .ok_or_else(|| Ars408Error::MissingMessage(message.to_owned()))?
            .clone();
        let mut index = [0; N];
        for (slot, name) in index.iter_mut().zip(names) {
            *slot = spec
                .signal_index(name)
                .ok_or_else(|| Ars408Error::MissingSignal {
                    message: message.to_owned(),
                    signal: name.to_owned(),
                })?;
        }
        Ok(Self { spec, index })
    }

    /// The used signals' values, in `NAMES` order (`NaN` for a multiplexed
    /// signal a user's DBC did not select).
    pub fn read(&self, frame: &CanFrame) -> Result<[f64; N], DbcError> {
        let decoded = self.spec.decode(frame)?;
        Ok(self.index.map(|i| decoded.value(i).unwrap_or(f64::NAN)))
    }
}

/// A decoded value as a whole non-negative code (ids, counts, enums);
/// `None` for anything else.
pub(super) fn code(value: f64) -> Option<u32> {
    let fits = value.is_finite() && value >= 0.0 && value <= f64::from(u32::MAX);
    (fits && value.fract() == 0.0).then_some(value as u32)
}

pub(super) mod radar_state {
    pub const NAMES: [&str; 14] = [
        "PersistentError",
        "InterferenceError",
        "TemperatureError",
        "TemporaryError",
        "VoltageError",
        "MaxDistanceCfg",
        "RadarPowerCfg",
        "SensorID",
        "SortIndex",
        "OutputTypeCfg",
        "SendQualityCfg",
        "SendExtInfoCfg",
        "MotionRxState",
        "RCS_Threshold",
    ];
    /// The five error bits come first, in this order.
    pub const ERRORS: usize = 5;
    pub const MAX_DISTANCE: usize = 5;
    pub const RADAR_POWER: usize = 6;
    pub const SENSOR_ID: usize = 7;
    pub const SORT_INDEX: usize = 8;
    pub const OUTPUT_TYPE: usize = 9;
    pub const SEND_QUALITY: usize = 10;
    pub const SEND_EXT_INFO: usize = 11;
    pub const MOTION_RX: usize = 12;
    pub const RCS_THRESHOLD: usize = 13;
}

pub(super) mod version {
    pub const NAMES: [&str; 5] = [
        "MajorRelease",
        "MinorRelease",
        "PatchLevel",
        "ExtendedRange",
        "CountryCode",
    ];
}

/// The RadarConfiguration signals the driver sets; every other signal of the
/// message is sent as raw 0 (its `*_valid` bit off).
pub(super) mod configuration {
    pub const NAMES: [&str; 14] = [
        "OutputType_valid",
        "OutputType",
        "MaxDistance_valid",
        "MaxDistance",
        "SendQuality_valid",
        "SendQuality",
        "SendExtInfo_valid",
        "SendExtInfo",
        "RadarPower_valid",
        "RadarPower",
        "SortIndex_valid",
        "SortIndex",
        "RCS_Threshold_valid",
        "RCS_Threshold",
    ];
}

/// `Cluster_1_General` and `Obj_1_General` share these names.
pub(super) mod general {
    pub const NAMES: [&str; 7] = [
        "ID", "DistLong", "DistLat", "VrelLong", "VrelLat", "DynProp", "RCS",
    ];
    pub const DIST_LONG: usize = 1;
    pub const DIST_LAT: usize = 2;
    pub const VREL_LONG: usize = 3;
    pub const VREL_LAT: usize = 4;
    pub const DYN_PROP: usize = 5;
    pub const RCS: usize = 6;
}

pub(super) mod cluster_quality {
    pub const NAMES: [&str; 5] = ["ID", "DistLong_rms", "DistLat_rms", "Pdh0", "InvalidState"];
}

pub(super) mod object_quality {
    pub const NAMES: [&str; 5] = [
        "ID",
        "DistLong_rms",
        "DistLat_rms",
        "ProbOfExist",
        "MeasState",
    ];
}

pub(super) mod object_extended {
    pub const NAMES: [&str; 5] = ["ID", "Length", "Width", "OrientationAngle", "Class"];
}

/// Every follow-up frame (general, quality, extended) carries the target's
/// id first.
pub(super) const ID: usize = 0;

/// The messages of one output's cycle.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct CycleMessages {
    /// Status: (count near, count far) for clusters; (count, -) for objects,
    /// then the measurement counter.
    pub status: Bound<3>,
    pub general: Bound<7>,
    pub quality: Bound<5>,
    /// Objects only.
    pub extended: Option<Bound<5>>,
}

/// Everything the driver decodes or encodes.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Layout {
    pub radar_state: Bound<14>,
    pub version: Bound<5>,
    /// Present when settings are to be sent.
    pub configuration: Option<Bound<14>>,
    pub cycle: CycleMessages,
    /// The standard ids of the list not selected (noted, not decoded); those
    /// the database does not have are simply other ids.
    pub other_output_ids: Vec<u32>,
}

impl Layout {
    /// Binds `db` (its ids already moved for the sensor id) for `output`.
    pub fn new(
        db: &CanDatabase,
        output: RadarOutput,
        configure: bool,
    ) -> Result<Self, Ars408Error> {
        let radar_state = Bound::new(db, "RadarState", radar_state::NAMES)?;
        let version = Bound::new(db, "VersionID", version::NAMES)?;
        let configuration = if configure {
            Some(Bound::new(db, "RadarConfiguration", configuration::NAMES)?)
        } else {
            None
        };
        let cycle = match output {
            RadarOutput::Clusters => CycleMessages {
                status: Bound::new(
                    db,
                    "Cluster_0_Status",
                    ["NofClustersNear", "NofClustersFar", "MeasCounter"],
                )?,
                general: Bound::new(db, "Cluster_1_General", general::NAMES)?,
                quality: Bound::new(db, "Cluster_2_Quality", cluster_quality::NAMES)?,
                extended: None,
            },
            RadarOutput::Objects => CycleMessages {
                // The objects' status has a single count: it is bound twice
                // (the "far" slot is read as 0 by the driver).
                status: Bound::new(
                    db,
                    "Obj_0_Status",
                    ["NofObjects", "NofObjects", "MeasCounter"],
                )?,
                general: Bound::new(db, "Obj_1_General", general::NAMES)?,
                quality: Bound::new(db, "Obj_2_Quality", object_quality::NAMES)?,
                extended: Some(Bound::new(db, "Obj_3_Extended", object_extended::NAMES)?),
            },
        };
        let other_names: &[&str] = match output {
            RadarOutput::Clusters => &[
                "Obj_0_Status",
                "Obj_1_General",
                "Obj_2_Quality",
                "Obj_3_Extended",
            ],
            RadarOutput::Objects => &["Cluster_0_Status", "Cluster_1_General", "Cluster_2_Quality"],
        };
        let other_output_ids = other_names
            .iter()
            .filter_map(|name| db.message(name))
            .filter(|m| !m.extended)
            .map(|m| m.id)
            .collect();
        Ok(Self {
            radar_state,
            version,
            configuration,
            cycle,
            other_output_ids,
        })
    }

    /// Which message of the radar a standard `id` is, if any.
    pub fn message_of(&self, id: u32) -> Option<RadarMessage> {
        let c = &self.cycle;
        let table = [
            (self.radar_state.spec.id, RadarMessage::State),
            (self.version.spec.id, RadarMessage::Version),
            (c.status.spec.id, RadarMessage::Status),
            (c.general.spec.id, RadarMessage::FollowUp(Section::General)),
            (c.quality.spec.id, RadarMessage::FollowUp(Section::Quality)),
        ];
        let extended = c
            .extended
            .as_ref()
            .map(|b| (b.spec.id, RadarMessage::FollowUp(Section::Extended)));
        table
            .into_iter()
            .chain(extended)
            .find_map(|(radar, message)| (radar == id).then_some(message))
    }
}

// Here, beside the messages they come in, rather than in `cycle`: which
// section a frame is follows from its id, and the cycle assembler builds on
// this layout, not the other way round.
/// The follow-up sections of a cycle's messages, in the order the radar
/// sends them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Section {
    General,
    Quality,
    Extended,
}

/// The radar's messages this driver reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum RadarMessage {
    State,
    Version,
    Status,
    FollowUp(Section),
}
