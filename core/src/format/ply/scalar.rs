//! The eight PLY scalar types, their names, sizes and byte decoding.

/// A PLY scalar property type (both the classic and the sized spellings).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ScalarType {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl ScalarType {
    /// The type of a header type name, e.g. `uchar` or `float32`.
    pub fn from_name(name: &str) -> Option<Self> {
        Some(match name {
            "char" | "int8" => Self::I8,
            "uchar" | "uint8" => Self::U8,
            "short" | "int16" => Self::I16,
            "ushort" | "uint16" => Self::U16,
            "int" | "int32" => Self::I32,
            "uint" | "uint32" => Self::U32,
            "float" | "float32" => Self::F32,
            "double" | "float64" => Self::F64,
            _ => return None,
        })
    }

    /// Size in bytes in a binary body.
    pub fn size(self) -> usize {
        match self {
            Self::I8 | Self::U8 => 1,
            Self::I16 | Self::U16 => 2,
            Self::I32 | Self::U32 | Self::F32 => 4,
            Self::F64 => 8,
        }
    }

    /// Whether the type can count the items of a list property.
    pub fn is_integer(self) -> bool {
        !matches!(self, Self::F32 | Self::F64)
    }

    /// The value stored at the start of `bytes`, or `None` if `bytes` is too short.
    /// Every type converts to f64 exactly.
    #[inline]
    pub fn decode(self, bytes: &[u8], big_endian: bool) -> Option<f64> {
        Some(match self {
            Self::I8 => *bytes.first()? as i8 as f64,
            Self::U8 => *bytes.first()? as f64,
            Self::I16 => i16::from_le_bytes(ordered(bytes, big_endian)?) as f64,
            Self::U16 => u16::from_le_bytes(ordered(bytes, big_endian)?) as f64,
            Self::I32 => i32::from_le_bytes(ordered(bytes, big_endian)?) as f64,
            Self::U32 => u32::from_le_bytes(ordered(bytes, big_endian)?) as f64,
            Self::F32 => f32::from_le_bytes(ordered(bytes, big_endian)?) as f64,
            Self::F64 => f64::from_le_bytes(ordered(bytes, big_endian)?),
        })
    }
}

/// The first `N` bytes of `bytes` in little-endian order.
#[inline]
fn ordered<const N: usize>(bytes: &[u8], big_endian: bool) -> Option<[u8; N]> {
    let mut array: [u8; N] = bytes.get(..N)?.try_into().ok()?;
    if big_endian {
        array.reverse();
    }
    Some(array)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decodes_both_byte_orders() {
        assert_eq!(
            ScalarType::I16.decode(&(-2i16).to_be_bytes(), true),
            Some(-2.0)
        );
        assert_eq!(
            ScalarType::U32.decode(&7u32.to_le_bytes(), false),
            Some(7.0)
        );
        assert_eq!(
            ScalarType::F64.decode(&1.5f64.to_be_bytes(), true),
            Some(1.5)
        );
        assert_eq!(ScalarType::I8.decode(&[0xff], false), Some(-1.0));
        assert_eq!(ScalarType::F32.decode(&[0, 0], false), None);
    }

    #[test]
    fn names_and_sizes_agree() {
        for (name, size) in [
            ("char", 1),
            ("uint8", 1),
            ("short", 2),
            ("uint16", 2),
            ("int", 4),
            ("float32", 4),
            ("double", 8),
        ] {
            assert_eq!(
                ScalarType::from_name(name).map(ScalarType::size),
                Some(size),
                "{name}"
            );
        }
        assert_eq!(ScalarType::from_name("half"), None);
    }
}
