//! How a value maps to CDR: the traits every ROS field type implements, their
//! impls for primitives, strings and sequences, and whole payloads.

use super::error::CdrError;
use super::reader::{CdrReader, MIN_STRING_BYTES};
use super::writer::CdrWriter;

/// A value CDR can write.
pub trait CdrEncode {
    /// Appends the value to `writer`.
    fn encode_cdr(&self, writer: &mut CdrWriter);
}

/// A value CDR can read into an owned Rust value.
pub trait CdrDecode: Sized {
    /// The fewest bytes one value takes, padding aside: bounds a sequence's
    /// element count by the bytes left before its elements are allocated.
    const MIN_CDR_BYTES: usize;

    /// Reads one value. `field` names where it sits, for errors (a struct's
    /// own fields name themselves).
    fn decode_cdr(reader: &mut CdrReader<'_>, field: &'static str) -> Result<Self, CdrError>;
}

/// A whole payload: the CDR_LE header and `value`.
pub fn encode_payload(value: &impl CdrEncode) -> Vec<u8> {
    let mut writer = CdrWriter::new();
    value.encode_cdr(&mut writer);
    writer.into_bytes()
}

/// Reads a whole payload with `read` (header first, then at most
/// [`super::MAX_TRAILING_PADDING`] zero bytes after it).
pub fn decode_payload_with<'a, T>(
    bytes: &'a [u8],
    read: impl FnOnce(&mut CdrReader<'a>) -> Result<T, CdrError>,
) -> Result<T, CdrError> {
    let mut reader = CdrReader::new(bytes)?;
    let value = read(&mut reader)?;
    reader.finish()?;
    Ok(value)
}

/// Reads a whole payload holding one `T`.
pub fn decode_payload<T: CdrDecode>(bytes: &[u8]) -> Result<T, CdrError> {
    decode_payload_with(bytes, |reader| T::decode_cdr(reader, "message"))
}

macro_rules! primitive_codec {
    ($($ty:ident),* $(,)?) => {$(
        impl CdrEncode for $ty {
            fn encode_cdr(&self, writer: &mut CdrWriter) {
                writer.$ty(*self);
            }
        }

        impl CdrDecode for $ty {
            const MIN_CDR_BYTES: usize = std::mem::size_of::<$ty>();

            fn decode_cdr(reader: &mut CdrReader<'_>, field: &'static str) -> Result<Self, CdrError> {
                reader.$ty(field)
            }
        }
    )*};
}

primitive_codec!(bool, u8, i8, i16, u16, i32, u32, i64, u64, f32, f64);

impl CdrEncode for String {
    fn encode_cdr(&self, writer: &mut CdrWriter) {
        writer.string(self);
    }
}

impl CdrDecode for String {
    const MIN_CDR_BYTES: usize = MIN_STRING_BYTES;

    fn decode_cdr(reader: &mut CdrReader<'_>, field: &'static str) -> Result<Self, CdrError> {
        reader.string(field).map(str::to_owned)
    }
}

/// `T[]`: a u32 count, then the elements.
impl<T: CdrEncode> CdrEncode for Vec<T> {
    fn encode_cdr(&self, writer: &mut CdrWriter) {
        writer.sequence_len(self.len());
        for element in self {
            element.encode_cdr(writer);
        }
    }
}

impl<T: CdrDecode> CdrDecode for Vec<T> {
    const MIN_CDR_BYTES: usize = 4;

    fn decode_cdr(reader: &mut CdrReader<'_>, field: &'static str) -> Result<Self, CdrError> {
        reader.elements(field, T::MIN_CDR_BYTES, |reader| {
            T::decode_cdr(reader, field)
        })
    }
}
