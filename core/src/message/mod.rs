//! The wire schema of shroud's messages (version 1): MessagePack maps with named
//! fields, bulk arrays as little-endian byte blobs, so that any language decodes a
//! message with a MessagePack library and a byte-to-array view (numpy's
//! `frombuffer`). Pure encode/decode with validation; transport lives in `nodes/`.

mod blob;
mod cloud;
mod error;
mod surrogate;

pub use cloud::{CloudMessage, SensorPose};
pub use error::MessageError;
pub use surrogate::{SurfaceMessage, SurrogateMessage};

/// The schema version every message carries; decoders refuse other versions.
pub const SCHEMA_VERSION: u16 = 1;

/// Checks a decoded message's version.
pub(crate) fn check_version(found: u16) -> Result<(), MessageError> {
    if found == SCHEMA_VERSION {
        Ok(())
    } else {
        Err(MessageError::Version {
            found,
            expected: SCHEMA_VERSION,
        })
    }
}
