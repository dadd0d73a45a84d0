//! The scalar types of binary cloud files (PLY properties, PCD fields): their
//! names in each format, sizes, byte decoding and text parsing.

/// A numeric type of one value in a cloud file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ScalarType {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    /// Only PCD has 64-bit integers (`I 8`, `U 8`).
    I64,
    U64,
    F32,
    F64,
}

impl ScalarType {
    /// The type of a PLY header type name, e.g. `uchar` or `float32` (PLY has no
    /// 64-bit integers).
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

    /// The type of a PCD `TYPE` letter (`I` signed, `U` unsigned, `F` floating
    /// point) with its `SIZE` in bytes, as PCL's `pcd_io` defines them: integers of
    /// 1, 2, 4 or 8 bytes, floats of 4 or 8.
    pub fn from_pcd(kind: char, size: usize) -> Option<Self> {
        Some(match (kind, size) {
            ('I', 1) => Self::I8,
            ('U', 1) => Self::U8,
            ('I', 2) => Self::I16,
            ('U', 2) => Self::U16,
            ('I', 4) => Self::I32,
            ('U', 4) => Self::U32,
            ('I', 8) => Self::I64,
            ('U', 8) => Self::U64,
            ('F', 4) => Self::F32,
            ('F', 8) => Self::F64,
            _ => return None,
        })
    }

    /// Size in bytes in a binary body.
    pub fn size(self) -> usize {
        match self {
            Self::I8 | Self::U8 => 1,
            Self::I16 | Self::U16 => 2,
            Self::I32 | Self::U32 | Self::F32 => 4,
            Self::I64 | Self::U64 | Self::F64 => 8,
        }
    }

    /// Whether the type can count the items of a list property.
    pub fn is_integer(self) -> bool {
        !matches!(self, Self::F32 | Self::F64)
    }

    /// The value stored at the start of `bytes`, or `None` if `bytes` is too short.
    /// Every type converts to f64 exactly, except 64-bit integers beyond 2^53,
    /// which round to the nearest f64.
    #[inline]
    pub fn decode(self, bytes: &[u8], big_endian: bool) -> Option<f64> {
        Some(match self {
            Self::I8 => *bytes.first()? as i8 as f64,
            Self::U8 => *bytes.first()? as f64,
            Self::I16 => i16::from_le_bytes(ordered(bytes, big_endian)?) as f64,
            Self::U16 => u16::from_le_bytes(ordered(bytes, big_endian)?) as f64,
            Self::I32 => i32::from_le_bytes(ordered(bytes, big_endian)?) as f64,
            Self::U32 => u32::from_le_bytes(ordered(bytes, big_endian)?) as f64,
            Self::I64 => i64::from_le_bytes(ordered(bytes, big_endian)?) as f64,
            Self::U64 => u64::from_le_bytes(ordered(bytes, big_endian)?) as f64,
            Self::F32 => f32::from_le_bytes(ordered(bytes, big_endian)?) as f64,
            Self::F64 => f64::from_le_bytes(ordered(bytes, big_endian)?),
        })
    }

    /// A text token as a value of this type at full precision, or `None` if it is
    /// not a number. `F32` tokens are parsed as f32 (and widened exactly), so a
    /// shortest-representation writer round-trips bit for bit; every other type
    /// goes through f64.
    pub fn parse_text(self, token: &str) -> Option<f64> {
        match self {
            Self::F32 => token.parse::<f32>().ok().map(f64::from),
            _ => token.parse::<f64>().ok(),
        }
    }

    /// The bytes of `value` as this type (cast as `as` casts), for tests that
    /// build binary bodies.
    #[cfg(test)]
    pub fn encode(self, value: f64, big_endian: bool) -> Vec<u8> {
        let mut bytes = match self {
            Self::I8 => (value as i8).to_le_bytes().to_vec(),
            Self::U8 => (value as u8).to_le_bytes().to_vec(),
            Self::I16 => (value as i16).to_le_bytes().to_vec(),
            Self::U16 => (value as u16).to_le_bytes().to_vec(),
            Self::I32 => (value as i32).to_le_bytes().to_vec(),
            Self::U32 => (value as u32).to_le_bytes().to_vec(),
            Self::I64 => (value as i64).to_le_bytes().to_vec(),
            Self::U64 => (value as u64).to_le_bytes().to_vec(),
            Self::F32 => (value as f32).to_le_bytes().to_vec(),
            Self::F64 => value.to_le_bytes().to_vec(),
        };
        if big_endian {
            bytes.reverse();
        }
        bytes
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
        assert_eq!(
            ScalarType::I64.decode(&(-3i64).to_le_bytes(), false),
            Some(-3.0)
        );
        assert_eq!(
            ScalarType::U64.decode(&u64::MAX.to_le_bytes(), false),
            Some(u64::MAX as f64)
        );
        assert_eq!(ScalarType::I8.decode(&[0xff], false), Some(-1.0));
        assert_eq!(ScalarType::F32.decode(&[0, 0], false), None);
        assert_eq!(ScalarType::U64.decode(&[0; 7], false), None);
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
        assert_eq!(ScalarType::from_name("int64"), None);
    }

    #[test]
    fn pcd_codes_have_their_sizes() {
        for kind in ['I', 'U'] {
            for size in [1, 2, 4, 8] {
                let ty = ScalarType::from_pcd(kind, size).unwrap();
                assert_eq!((ty.size(), ty.is_integer()), (size, true), "{kind} {size}");
            }
        }
        for size in [4, 8] {
            let ty = ScalarType::from_pcd('F', size).unwrap();
            assert_eq!((ty.size(), ty.is_integer()), (size, false));
        }
        for (kind, size) in [('F', 2), ('F', 1), ('I', 3), ('U', 16), ('X', 4), ('f', 4)] {
            assert_eq!(ScalarType::from_pcd(kind, size), None, "{kind} {size}");
        }
    }

    #[test]
    fn text_keeps_each_types_precision() {
        assert_eq!(ScalarType::F32.parse_text("0.1"), Some(0.1f32 as f64));
        assert_eq!(ScalarType::F64.parse_text("0.1"), Some(0.1));
        assert!(ScalarType::F32.parse_text("nan").unwrap().is_nan());
        assert_eq!(ScalarType::U8.parse_text("two"), None);
    }
}
