//! Why an ARS408 driver cannot start: a bad setting, or a database that
//! lacks a message or signal the driver reads or writes.

use crate::dbc::DbcError;
use thiserror::Error;

#[derive(Debug, Clone, PartialEq, Error)]
pub enum Ars408Error {
    #[error("ARS408 setting {name}: {reason}")]
    BadSetting { name: &'static str, reason: String },
    #[error("the ARS408 database has no message {0} (standard id) the driver needs")]
    MissingMessage(String),
    #[error("the ARS408 database's message {message} has no signal {signal}")]
    MissingSignal { message: String, signal: String },
    #[error("the ARS408 database's ids moved for sensor id {sensor_id}: {source}")]
    IdOffset { sensor_id: u8, source: DbcError },
    #[error("the ARS408 RadarConfiguration frame cannot be encoded: {0}")]
    Configuration(DbcError),
}
