//! Classic CDR (OMG DDS-XTypes 1.3 §7.4.2 "XCDR1", as ROS 2's rmw layers
//! write it): a 4-byte encapsulation header, then each primitive aligned to
//! its size (at most 8) counted from the byte after the header.

mod codec;
mod encapsulation;
mod error;
mod reader;
mod writer;

pub use codec::{decode_payload, decode_payload_with, encode_payload, CdrDecode, CdrEncode};
pub use encapsulation::{Endianness, CDR_BE, CDR_LE, HEADER_LEN};
pub use error::CdrError;
pub use reader::{CdrReader, MAX_TRAILING_PADDING, MIN_STRING_BYTES};
pub use writer::CdrWriter;
