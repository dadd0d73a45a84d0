//! rmw_zenoh sample attachments (shroud-ros2's `Attachment::decode`): what
//! decodes must encode to the same 33 bytes.

use crate::check::named;
use shroud_ros2::Attachment;

pub fn run(data: &[u8]) {
    match Attachment::decode(data) {
        Ok(attachment) => assert!(attachment.encode() == data, "re-encoding changed the bytes"),
        Err(e) => named(&e),
    }
}

/// The first sample of a publisher.
pub fn seeds() -> Vec<Vec<u8>> {
    let first = Attachment {
        sequence_number: 1,
        source_timestamp_ns: 1_700_000_000_000_000_000,
        gid: *b"0123456789abcdef",
    };
    vec![first.encode().to_vec()]
}
