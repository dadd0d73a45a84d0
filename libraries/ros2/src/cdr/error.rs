//! Why a CDR payload could not be decoded; every variant names the field.

/// A CDR payload that does not decode. `field` is `Type.field` as in the ROS
/// `.msg` definition (`"PointCloud2.data"`).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum CdrError {
    #[error("{field}: needs {needed} more bytes, {remaining} remain")]
    Truncated {
        field: &'static str,
        needed: usize,
        remaining: usize,
    },
    #[error(
        "encapsulation header: representation {identifier:02x?} is not classic CDR \
         (00 01 little endian or 00 00 big endian)"
    )]
    Header { identifier: [u8; 2] },
    #[error("{field}: {count} elements of at least {element_bytes} bytes each cannot fit in the {remaining} bytes left")]
    Count {
        field: &'static str,
        count: u32,
        element_bytes: usize,
        remaining: usize,
    },
    #[error("{field}: the string is not UTF-8")]
    NotUtf8 { field: &'static str },
    #[error("{field}: the string does not end with a NUL byte (length {length})")]
    MissingNul { field: &'static str, length: u32 },
    #[error("{field}: bool byte {value} is neither 0 nor 1")]
    Bool { field: &'static str, value: u8 },
    #[error("{count} bytes after the message (at most {allowed} zero padding bytes are allowed)")]
    TrailingBytes { count: usize, allowed: usize },
}
