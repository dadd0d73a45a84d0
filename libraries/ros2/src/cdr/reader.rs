//! Reads a CDR payload: primitives aligned to their size from the byte after
//! the header (XCDR1, DDS-XTypes 1.3 §7.4.2), strings, bytes and sequence
//! counts checked against what is left before anything is allocated.

use super::encapsulation::{read_header, Endianness, HEADER_LEN};
use super::error::CdrError;

/// The trailing bytes [`CdrReader::finish`] accepts after the last field,
/// all zero: Fast-DDS pads a serialized payload to a multiple of 4 (and
/// counts the padding in the header's options); nothing else may follow.
pub const MAX_TRAILING_PADDING: usize = 3;

/// The fewest bytes a string takes: its u32 length and the NUL.
pub const MIN_STRING_BYTES: usize = 5;

/// A cursor over one CDR payload (header included); values borrow from it.
#[derive(Debug, Clone)]
pub struct CdrReader<'a> {
    bytes: &'a [u8],
    position: usize,
    endianness: Endianness,
}

macro_rules! read_primitives {
    ($($name:ident: $ty:ty),* $(,)?) => {$(
        #[doc = concat!("Reads a `", stringify!($ty), "` aligned to its size.")]
        pub fn $name(&mut self, field: &'static str) -> Result<$ty, CdrError> {
            let bytes = self.array(field)?;
            Ok(match self.endianness {
                Endianness::Little => <$ty>::from_le_bytes(bytes),
                Endianness::Big => <$ty>::from_be_bytes(bytes),
            })
        }
    )*};
}

impl<'a> CdrReader<'a> {
    /// A reader after `bytes`' encapsulation header (CDR_LE or CDR_BE).
    pub fn new(bytes: &'a [u8]) -> Result<Self, CdrError> {
        let endianness = read_header(bytes)?;
        Ok(Self {
            bytes,
            position: HEADER_LEN,
            endianness,
        })
    }

    /// The byte order the header announced.
    pub fn endianness(&self) -> Endianness {
        self.endianness
    }

    /// The bytes not read yet.
    pub fn remaining(&self) -> usize {
        self.bytes.len() - self.position
    }

    read_primitives! { u8: u8, i8: i8, i16: i16, u16: u16, i32: i32, u32: u32, i64: i64, u64: u64, f32: f32, f64: f64 }

    /// Reads a bool: one byte, 0 or 1 (anything else is an error).
    pub fn bool(&mut self, field: &'static str) -> Result<bool, CdrError> {
        match self.u8(field)? {
            0 => Ok(false),
            1 => Ok(true),
            value => Err(CdrError::Bool { field, value }),
        }
    }

    /// Reads a string: a u32 length counting the NUL, the UTF-8 bytes, a NUL.
    pub fn string(&mut self, field: &'static str) -> Result<&'a str, CdrError> {
        let length = self.u32(field)?;
        let bytes = self.take(field, length as usize)?;
        let Some((&0, text)) = bytes.split_last() else {
            return Err(CdrError::MissingNul { field, length });
        };
        std::str::from_utf8(text).map_err(|_| CdrError::NotUtf8 { field })
    }

    /// Reads `len` raw bytes (no alignment).
    pub fn bytes(&mut self, field: &'static str, len: usize) -> Result<&'a [u8], CdrError> {
        self.take(field, len)
    }

    /// Reads a `uint8[]`: a u32 count, then the bytes, borrowed.
    pub fn byte_sequence(&mut self, field: &'static str) -> Result<&'a [u8], CdrError> {
        let len = self.sequence_len(field, 1)?;
        self.take(field, len)
    }

    /// Reads a sequence's u32 element count and refuses one whose elements,
    /// at `min_element_bytes` each (padding aside), cannot fit in the bytes
    /// left: a caller may then allocate `count` elements.
    pub fn sequence_len(
        &mut self,
        field: &'static str,
        min_element_bytes: usize,
    ) -> Result<usize, CdrError> {
        let count = self.u32(field)?;
        let element_bytes = min_element_bytes.max(1);
        let remaining = self.remaining();
        match (count as usize).checked_mul(element_bytes) {
            Some(total) if total <= remaining => Ok(count as usize),
            _ => Err(CdrError::Count {
                field,
                count,
                element_bytes,
                remaining,
            }),
        }
    }

    /// Reads a sequence of elements of at least `min_element_bytes` each,
    /// each read by `read`.
    pub fn elements<T>(
        &mut self,
        field: &'static str,
        min_element_bytes: usize,
        mut read: impl FnMut(&mut Self) -> Result<T, CdrError>,
    ) -> Result<Vec<T>, CdrError> {
        let count = self.sequence_len(field, min_element_bytes)?;
        let mut values = Vec::with_capacity(count);
        for _ in 0..count {
            values.push(read(self)?);
        }
        Ok(values)
    }

    /// Ends the payload: at most [`MAX_TRAILING_PADDING`] zero bytes may follow.
    pub fn finish(self) -> Result<(), CdrError> {
        let rest = &self.bytes[self.position..];
        if rest.len() <= MAX_TRAILING_PADDING && rest.iter().all(|&b| b == 0) {
            return Ok(());
        }
        Err(CdrError::TrailingBytes {
            count: rest.len(),
            allowed: MAX_TRAILING_PADDING,
        })
    }

    /// Skips the padding before a primitive of `N` bytes, then reads it.
    fn array<const N: usize>(&mut self, field: &'static str) -> Result<[u8; N], CdrError> {
        let padding = (N - (self.position - HEADER_LEN) % N) % N;
        self.take(field, padding)?;
        let bytes = self.take(field, N)?;
        Ok(bytes.try_into().expect("take returns N bytes"))
    }

    fn take(&mut self, field: &'static str, len: usize) -> Result<&'a [u8], CdrError> {
        let remaining = self.remaining();
        if len > remaining {
            return Err(CdrError::Truncated {
                field,
                needed: len,
                remaining,
            });
        }
        let bytes = &self.bytes[self.position..self.position + len];
        self.position += len;
        Ok(bytes)
    }
}
