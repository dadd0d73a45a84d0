//! The QoS segment of a liveliness token (liveliness_utils.cpp@3411fdec,
//! `qos_to_keyexpr` / `keyexpr_to_qos`):
//! `rel:dur:hist,depth:dl_s,dl_ns:ls_s,ls_ns:liv,lease_s,lease_ns`, numbers
//! from rmw's enums (rmw/types.h), an empty field meaning rmw_zenoh's default
//! (qos.cpp@7efeee2b: reliable, volatile, keep last 42, infinite deadline,
//! lifespan and lease, automatic liveliness).
//!
//! shroud writes reliability, durability, history and depth explicitly (the
//! defaults changed between branches, rmw_zenoh #521) and leaves deadline,
//! lifespan and liveliness empty: rmw_zenoh's defaults, which shroud does
//! not model (`2:2:1,5:,:,:,,` for best effort, volatile, keep last 5).

use super::error::RmwError;

/// rmw_zenoh's history depth when the token leaves it empty (qos.cpp@7efeee2b).
pub const RMW_ZENOH_DEFAULT_DEPTH: u32 = 42;

/// Whether every sample must arrive.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reliability {
    /// `RMW_QOS_POLICY_RELIABILITY_RELIABLE` = 1.
    Reliable,
    /// `RMW_QOS_POLICY_RELIABILITY_BEST_EFFORT` = 2.
    BestEffort,
}

/// Whether late subscribers get the last samples.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Durability {
    /// `RMW_QOS_POLICY_DURABILITY_TRANSIENT_LOCAL` = 1.
    TransientLocal,
    /// `RMW_QOS_POLICY_DURABILITY_VOLATILE` = 2.
    Volatile,
}

/// How many samples are queued.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum History {
    /// `RMW_QOS_POLICY_HISTORY_KEEP_LAST` = 1, with its depth.
    KeepLast(u32),
    /// `RMW_QOS_POLICY_HISTORY_KEEP_ALL` = 2.
    KeepAll,
}

/// The QoS policies shroud sets on an entity.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct QosProfile {
    pub reliability: Reliability,
    pub durability: Durability,
    pub history: History,
}

impl Default for QosProfile {
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl QosProfile {
    /// rmw's `rmw_qos_profile_default`: reliable, volatile, keep last 10.
    pub const DEFAULT: Self = Self {
        reliability: Reliability::Reliable,
        durability: Durability::Volatile,
        history: History::KeepLast(10),
    };
    /// rmw's `rmw_qos_profile_sensor_data`: best effort, volatile, keep last 5.
    pub const SENSOR_DATA: Self = Self {
        reliability: Reliability::BestEffort,
        durability: Durability::Volatile,
        history: History::KeepLast(5),
    };

    /// The token's QoS segment, e.g. `2:2:1,5:,:,:,,`.
    pub fn to_keyexpr(&self) -> String {
        let reliability = match self.reliability {
            Reliability::Reliable => 1,
            Reliability::BestEffort => 2,
        };
        let durability = match self.durability {
            Durability::TransientLocal => 1,
            Durability::Volatile => 2,
        };
        let history = match self.history {
            History::KeepLast(depth) => format!("1,{depth}"),
            History::KeepAll => "2,".to_string(),
        };
        format!("{reliability}:{durability}:{history}:,:,:,,")
    }

    /// Reads a QoS segment as rmw_zenoh's `keyexpr_to_qos` does: at least 6
    /// `:`-parts, empty fields or `0` (system default) take rmw_zenoh's
    /// defaults, deadline, lifespan and liveliness must be empty or decimal
    /// numbers (and are not kept).
    pub fn parse(qos: &str) -> Result<Self, RmwError> {
        let error = |problem: String| RmwError::Qos {
            qos: qos.to_string(),
            problem,
        };
        let parts: Vec<&str> = qos.split(':').collect();
        if parts.len() < 6 {
            return Err(error(format!(
                "{} ':'-separated parts, needs 6",
                parts.len()
            )));
        }
        let history_parts = components(parts[2], "history", 2).map_err(error)?;
        for (index, name, count) in [(3, "deadline", 2), (4, "lifespan", 2), (5, "liveliness", 3)] {
            for value in components(parts[index], name, count).map_err(error)? {
                number(value, name).map_err(error)?;
            }
        }
        let reliability = match parts[0] {
            "" | "0" | "1" => Reliability::Reliable,
            "2" => Reliability::BestEffort,
            other => return Err(error(format!("reliability {other:?} is not 1 or 2"))),
        };
        let durability = match parts[1] {
            "1" => Durability::TransientLocal,
            "" | "0" | "2" => Durability::Volatile,
            other => return Err(error(format!("durability {other:?} is not 1 or 2"))),
        };
        let depth = number(history_parts[1], "depth")
            .map_err(error)?
            .map_or(Ok(RMW_ZENOH_DEFAULT_DEPTH), u32::try_from)
            .map_err(|_| error("depth exceeds u32".to_string()))?;
        let history = match history_parts[0] {
            "" | "0" | "1" => History::KeepLast(depth),
            "2" => History::KeepAll,
            other => return Err(error(format!("history {other:?} is not 1 or 2"))),
        };
        Ok(Self {
            reliability,
            durability,
            history,
        })
    }
}

/// The `,`-separated components of one QoS part, at least `count` of them.
fn components<'a>(part: &'a str, name: &str, count: usize) -> Result<Vec<&'a str>, String> {
    let values: Vec<&str> = part.split(',').collect();
    if values.len() < count {
        return Err(format!(
            "{name} {part:?} has {} ','-separated values, needs {count}",
            values.len()
        ));
    }
    Ok(values)
}

/// An empty field (None) or a decimal number (strtoul's digits only).
fn number(value: &str, name: &str) -> Result<Option<u64>, String> {
    if value.is_empty() {
        return Ok(None);
    }
    if !value.bytes().all(|b| b.is_ascii_digit()) {
        return Err(format!("{name} {value:?} is not a decimal number"));
    }
    value
        .parse()
        .map(Some)
        .map_err(|_| format!("{name} {value:?} overflows"))
}
