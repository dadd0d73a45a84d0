//! A classic CAN 2.0 frame as plain data: the common currency of the CAN sensor
//! protocol, SLCAN, candump logs and the node-side sources.

use crate::IngestError;

/// Largest standard (11-bit) identifier.
pub const MAX_STANDARD_ID: u32 = 0x7FF;
/// Largest extended (29-bit) identifier.
pub const MAX_EXTENDED_ID: u32 = 0x1FFF_FFFF;

/// A classic CAN frame: identifier, format, and up to 8 data bytes (`len` of
/// them valid; the rest of `data` is zero). A remote (RTR) frame has `len` as
/// its requested length and no data.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct CanFrame {
    pub id: u32,
    pub extended: bool,
    pub remote: bool,
    pub len: u8,
    pub data: [u8; 8],
}

impl CanFrame {
    /// A data frame. Fails if the id does not fit its format or `data` has more
    /// than 8 bytes.
    pub fn new(id: u32, extended: bool, data: &[u8]) -> Result<Self, IngestError> {
        check(id, extended, data.len())?;
        let mut bytes = [0; 8];
        bytes[..data.len()].copy_from_slice(data);
        Ok(Self {
            id,
            extended,
            remote: false,
            len: data.len() as u8,
            data: bytes,
        })
    }

    /// A remote transmission request for `len` bytes.
    pub fn remote(id: u32, extended: bool, len: u8) -> Result<Self, IngestError> {
        check(id, extended, len.into())?;
        Ok(Self {
            id,
            extended,
            remote: true,
            len,
            data: [0; 8],
        })
    }

    /// The valid data bytes (empty for a remote frame).
    pub fn payload(&self) -> &[u8] {
        if self.remote {
            &[]
        } else {
            &self.data[..usize::from(self.len.min(8))]
        }
    }
}

fn check(id: u32, extended: bool, len: usize) -> Result<(), IngestError> {
    let max = if extended {
        MAX_EXTENDED_ID
    } else {
        MAX_STANDARD_ID
    };
    if id > max {
        return Err(IngestError::Malformed {
            what: "CAN frame",
            reason: format!("id {id:#x} exceeds {max:#x}"),
        });
    }
    if len > 8 {
        return Err(IngestError::Oversize {
            what: "CAN data length",
            found: len,
            limit: 8,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_check_their_id_and_length() {
        let f = CanFrame::new(0x123, false, &[1, 2, 3]).unwrap();
        assert_eq!(f.payload(), &[1, 2, 3]);
        assert_eq!(f.data, [1, 2, 3, 0, 0, 0, 0, 0]);
        assert!(CanFrame::new(0x800, false, &[]).is_err());
        assert!(CanFrame::new(0x800, true, &[]).is_ok());
        assert!(CanFrame::new(0x2000_0000, true, &[]).is_err());
        assert!(CanFrame::new(1, false, &[0; 9]).is_err());
        let r = CanFrame::remote(0x10, false, 4).unwrap();
        assert!(r.payload().is_empty());
        assert!(CanFrame::remote(0x10, false, 9).is_err());
    }
}
