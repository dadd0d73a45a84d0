//! Why a DBC text was refused, or a frame could not be decoded or encoded with
//! it: one named error per failure.

use thiserror::Error;

/// Every way loading a DBC database or coding a frame with it can fail.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum DbcError {
    /// The `can-dbc` parser refused the text (its message, with line:col where
    /// it gives one).
    #[error("DBC parse error: {0}")]
    Parse(String),
    #[error("DBC text of {bytes} bytes exceeds the limit of {limit}")]
    TooLarge { bytes: usize, limit: usize },
    #[error("DBC defines {found} messages, more than the limit of {limit}")]
    TooManyMessages { found: usize, limit: usize },
    #[error("messages {first} and {second} share the CAN id {id:#x}{}", if *.extended { " (extended)" } else { "" })]
    DuplicateId {
        id: u32,
        extended: bool,
        first: String,
        second: String,
    },
    #[error("two messages are named {0}")]
    DuplicateMessage(String),
    #[error("message {message} has two signals named {signal}")]
    DuplicateSignal { message: String, signal: String },
    #[error("message {message}: CAN id {id:#x} does not fit its format (standard ids end at 0x7ff, extended at 0x1fffffff)")]
    BadId { message: String, id: u32 },
    #[error("message {message}: length {len} exceeds the 8 bytes of a classic CAN frame")]
    BadLength { message: String, len: u64 },
    #[error("message {message}: signal {signal} (start bit {start_bit}, {size} bits) does not fit in {len} bytes")]
    SignalOutOfFrame {
        message: String,
        signal: String,
        start_bit: u64,
        size: u64,
        len: u8,
    },
    #[error("message {message}: signal {signal}: {reason}")]
    BadSignal {
        message: String,
        signal: String,
        reason: String,
    },
    #[error("message {message}: bad multiplexing: {reason}")]
    BadMultiplex { message: String, reason: String },
    #[error("no message named {0}")]
    UnknownMessage(String),
    #[error("message {message} has no signal named {signal}")]
    UnknownSignal { message: String, signal: String },
    #[error("message {message}: frame has {found} data bytes, the message needs {expected}")]
    ShortFrame {
        message: String,
        found: usize,
        expected: usize,
    },
    #[error("message {message}: signal {signal} = {value} is outside [{min}, {max}]")]
    ValueOutOfRange {
        message: String,
        signal: String,
        value: f64,
        min: f64,
        max: f64,
    },
    #[error("message {message}: no value given for signal {signal}")]
    MissingSignal { message: String, signal: String },
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_name_the_problem() {
        let e = DbcError::DuplicateId {
            id: 0x201,
            extended: false,
            first: "A".into(),
            second: "B".into(),
        };
        assert_eq!(e.to_string(), "messages A and B share the CAN id 0x201");
        let e = DbcError::SignalOutOfFrame {
            message: "M".into(),
            signal: "S".into(),
            start_bit: 60,
            size: 8,
            len: 8,
        };
        assert!(e.to_string().contains("start bit 60"));
    }
}
