//! Writes a CDR payload: the CDR_LE header, then primitives aligned to their
//! size from the byte after it (XCDR1, DDS-XTypes 1.3 §7.4.2), padding zero.

use super::encapsulation::{little_endian_header, HEADER_LEN};

/// A little-endian CDR payload being written (header included).
#[derive(Debug, Clone)]
pub struct CdrWriter {
    bytes: Vec<u8>,
}

impl Default for CdrWriter {
    fn default() -> Self {
        Self::new()
    }
}

macro_rules! write_primitives {
    ($($name:ident: $ty:ty),* $(,)?) => {$(
        #[doc = concat!("Writes a `", stringify!($ty), "` aligned to its size.")]
        pub fn $name(&mut self, value: $ty) {
            self.align(std::mem::size_of::<$ty>());
            self.bytes.extend_from_slice(&value.to_le_bytes());
        }
    )*};
}

impl CdrWriter {
    /// A payload holding the CDR_LE header (`00 01 00 00`).
    pub fn new() -> Self {
        Self::with_capacity(0)
    }

    /// The same with room for `capacity` bytes of message, so that a large
    /// message (a cloud's data) is copied once, not again as the buffer grows.
    pub fn with_capacity(capacity: usize) -> Self {
        let mut bytes = Vec::with_capacity(HEADER_LEN + capacity);
        bytes.extend_from_slice(&little_endian_header());
        Self { bytes }
    }

    write_primitives! { u8: u8, i8: i8, i16: i16, u16: u16, i32: i32, u32: u32, i64: i64, u64: u64, f32: f32, f64: f64 }

    /// Writes a bool as one byte, 0 or 1.
    pub fn bool(&mut self, value: bool) {
        self.u8(u8::from(value));
    }

    /// Writes a string: a u32 length counting the NUL, the bytes, a NUL.
    pub fn string(&mut self, value: &str) {
        self.sequence_len(value.len() + 1);
        self.bytes.extend_from_slice(value.as_bytes());
        self.bytes.push(0);
    }

    /// Writes raw bytes (no alignment, no count).
    pub fn bytes(&mut self, value: &[u8]) {
        self.bytes.extend_from_slice(value);
    }

    /// Writes a `uint8[]`: a u32 count, then the bytes.
    pub fn byte_sequence(&mut self, value: &[u8]) {
        self.sequence_len(value.len());
        self.bytes(value);
    }

    /// Writes a sequence's u32 element count.
    ///
    /// # Panics
    /// If `len` exceeds `u32::MAX`: CDR cannot count such a sequence.
    pub fn sequence_len(&mut self, len: usize) {
        let count =
            u32::try_from(len).expect("a CDR sequence or string holds at most u32::MAX elements");
        self.u32(count);
    }

    /// The payload.
    pub fn into_bytes(self) -> Vec<u8> {
        self.bytes
    }

    fn align(&mut self, size: usize) {
        let padding = (size - (self.bytes.len() - HEADER_LEN) % size) % size;
        self.bytes.resize(self.bytes.len() + padding, 0);
    }
}
