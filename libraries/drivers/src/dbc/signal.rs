//! One DBC signal: where its bits sit in a classic 8-byte CAN payload (Intel or
//! Motorola order), its sign, scaling and range, and the codec between raw bits
//! and physical values. This is the decoder's hot path: no allocation.
//!
//! Bit numbering (Vector DBC convention): bit `i` is bit `i % 8` of byte `i / 8`.
//! An Intel (`@1`) signal's start bit is its least significant bit and its bits
//! go up linearly. A Motorola (`@0`) signal's start bit is its most significant
//! bit in that "sawtooth" numbering; read as one big-endian word
//! (`u64::from_be_bytes`), the signal is contiguous below that bit.

use super::DbcError;

/// The order of a signal's bits in the payload.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ByteOrder {
    /// Little-endian (`@1`): start bit = least significant bit.
    Intel,
    /// Big-endian (`@0`): start bit = most significant bit (sawtooth numbering).
    Motorola,
}

/// A signal's role in DBC multiplexing (`M` / `m<n>`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Multiplex {
    /// Always present.
    Plain,
    /// The switch: its raw value selects the multiplexed signals.
    Multiplexor,
    /// Present only when the multiplexor's raw value equals this.
    Multiplexed(u64),
}

/// A signal of a message, as declared by an `SG_` line.
#[derive(Debug, Clone, PartialEq)]
pub struct SignalSpec {
    pub name: String,
    /// DBC convention: Intel = LSB position, Motorola = MSB position (sawtooth numbering).
    pub start_bit: u16,
    /// 1..=64 bits.
    pub size: u8,
    pub order: ByteOrder,
    pub signed: bool,
    pub factor: f64,
    pub offset: f64,
    /// DBC `[min|max]`; `min == max` means "no range given".
    pub min: f64,
    pub max: f64,
    pub unit: String,
    pub multiplex: Multiplex,
}

impl SignalSpec {
    /// The raw bits, right-aligned (sign not applied). A spec whose bits do not
    /// fit the 8 bytes (never loaded from a DBC: they are checked) reads 0.
    pub fn raw(&self, data: &[u8; 8]) -> u64 {
        match self.shift() {
            Some(shift) => (self.word(data) >> shift) & self.mask(),
            None => 0,
        }
    }

    /// The physical value: sign-extended raw * factor + offset.
    pub fn decode(&self, data: &[u8; 8]) -> f64 {
        let raw = self.raw(data);
        let raw = if self.signed {
            sign_extend(raw, self.size) as f64
        } else {
            raw as f64
        };
        raw * self.factor + self.offset
    }

    /// Writes `value` into its bits of `data`, rounded to the nearest raw step.
    /// Refuses (`ValueOutOfRange`, with an empty `message` for the caller to
    /// fill) non-finite values, values outside `[min, max]` when a range is
    /// given (with half a step of slack, so the range's own ends always
    /// encode), and raw values that do not fit `size` bits.
    pub fn encode(&self, value: f64, data: &mut [u8; 8]) -> Result<(), DbcError> {
        let (lo, hi) = self.physical_bounds();
        let out_of_range = |min: f64, max: f64| DbcError::ValueOutOfRange {
            message: String::new(),
            signal: self.name.clone(),
            value,
            min,
            max,
        };
        let Some(shift) = self.shift() else {
            return Err(out_of_range(lo, hi));
        };
        if !value.is_finite() {
            return Err(out_of_range(lo, hi));
        }
        if self.has_range() {
            let slack = self.factor.abs() / 2.0;
            if !(value >= self.min - slack && value <= self.max + slack) {
                return Err(out_of_range(self.min, self.max));
            }
        }
        let raw = ((value - self.offset) / self.factor).round();
        // The rounded value must itself lie in the range: the slack admits a
        // value that rounds onto an end, never one that rounds past it.
        let encoded = raw * self.factor + self.offset;
        let epsilon = 1e-9 * self.factor.abs().max(encoded.abs());
        if self.has_range() && !(encoded >= self.min - epsilon && encoded <= self.max + epsilon) {
            return Err(out_of_range(self.min, self.max));
        }
        let bits = self.raw_bits(raw).ok_or_else(|| out_of_range(lo, hi))?;
        let mask = self.mask() << shift;
        let word = (self.word(data) & !mask) | ((bits << shift) & mask);
        *data = match self.order {
            ByteOrder::Intel => word.to_le_bytes(),
            ByteOrder::Motorola => word.to_be_bytes(),
        };
        Ok(())
    }

    /// Whether the DBC gave a `[min|max]` range (`min == max` means none).
    pub fn has_range(&self) -> bool {
        self.min != self.max
    }

    /// Whether the signal's bits lie within the first `len` bytes.
    pub fn fits(&self, len: u8) -> bool {
        let Some(shift) = self.shift() else {
            return false;
        };
        let len = u32::from(len.min(8));
        match self.order {
            ByteOrder::Intel => shift + u32::from(self.size) <= len * 8,
            // Byte k of the frame holds big-endian bits (7 - k) * 8 ..= (7 - k) * 8 + 7.
            ByteOrder::Motorola => shift >= (8 - len) * 8,
        }
    }

    /// The physical values of the smallest and largest raw values `size` bits
    /// hold, lowest first.
    pub fn physical_bounds(&self) -> (f64, f64) {
        let size = i32::from(self.size.min(64));
        let (raw_lo, raw_hi) = if self.signed {
            (-(2f64.powi(size - 1)), 2f64.powi(size - 1) - 1.0)
        } else {
            (0.0, 2f64.powi(size) - 1.0)
        };
        let a = raw_lo * self.factor + self.offset;
        let b = raw_hi * self.factor + self.offset;
        if a <= b {
            (a, b)
        } else {
            (b, a)
        }
    }

    /// The payload as the word this signal's order reads.
    fn word(&self, data: &[u8; 8]) -> u64 {
        match self.order {
            ByteOrder::Intel => u64::from_le_bytes(*data),
            ByteOrder::Motorola => u64::from_be_bytes(*data),
        }
    }

    /// Where the signal's least significant bit sits in [`Self::word`]; `None`
    /// when the size is 0 or over 64 or the bits leave the 64-bit word.
    fn shift(&self) -> Option<u32> {
        let size = u32::from(self.size);
        let start = u32::from(self.start_bit);
        if size == 0 || size > 64 || start > 63 {
            return None;
        }
        match self.order {
            ByteOrder::Intel => (start + size <= 64).then_some(start),
            ByteOrder::Motorola => {
                let msb = (7 - start / 8) * 8 + start % 8;
                msb.checked_sub(size - 1)
            }
        }
    }

    fn mask(&self) -> u64 {
        match self.size {
            0 => 0,
            s if s >= 64 => u64::MAX,
            s => (1u64 << s) - 1,
        }
    }

    /// The raw value's bits, or `None` when the (integral) `raw` does not fit
    /// `size` bits of this signedness. Bounds are powers of two, exact in f64.
    fn raw_bits(&self, raw: f64) -> Option<u64> {
        let size = i32::from(self.size);
        if self.signed {
            let half = 2f64.powi(size - 1);
            // `as` saturates, but the range check keeps it exact.
            (raw >= -half && raw < half).then(|| (raw as i64) as u64 & self.mask())
        } else {
            (raw >= 0.0 && raw < 2f64.powi(size)).then_some(raw as u64)
        }
    }
}

/// Two's complement sign extension of the low `size` bits of `raw`.
fn sign_extend(raw: u64, size: u8) -> i64 {
    match size {
        1..=63 => {
            let unused = 64 - u32::from(size);
            ((raw << unused) as i64) >> unused
        }
        _ => raw as i64,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(start_bit: u16, size: u8, order: ByteOrder, signed: bool) -> SignalSpec {
        SignalSpec {
            name: "S".into(),
            start_bit,
            size,
            order,
            signed,
            factor: 1.0,
            offset: 0.0,
            min: 0.0,
            max: 0.0,
            unit: String::new(),
            multiplex: Multiplex::Plain,
        }
    }

    #[test]
    fn intel_straddles_bytes_upward() {
        // 12 bits from bit 4: byte 0 bits 7..4 hold the low nibble, byte 1 the rest.
        let s = spec(4, 12, ByteOrder::Intel, false);
        let data = [0xA0, 0xBC, 0, 0, 0, 0, 0, 0];
        assert_eq!(s.raw(&data), 0xBCA);
        let mut out = [0; 8];
        s.encode(f64::from(0xBCA), &mut out).unwrap();
        assert_eq!(out, data);
    }

    #[test]
    fn motorola_straddles_bytes_downward() {
        // MSB at bit 3 (byte 0 bit 3), 12 bits: byte 0 bits 3..0, then byte 1.
        let s = spec(3, 12, ByteOrder::Motorola, false);
        let data = [0x0A, 0xBC, 0, 0, 0, 0, 0, 0];
        assert_eq!(s.raw(&data), 0xABC);
        let mut out = [0xFF; 8];
        s.encode(f64::from(0xABC), &mut out).unwrap();
        assert_eq!(out, [0xFA, 0xBC, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF]);
    }

    #[test]
    fn signed_values_sign_extend() {
        let s = spec(8, 8, ByteOrder::Intel, true);
        assert_eq!(s.decode(&[0, 0xFE, 0, 0, 0, 0, 0, 0]), -2.0);
        assert_eq!(s.decode(&[0, 0x7F, 0, 0, 0, 0, 0, 0]), 127.0);
        assert_eq!(s.decode(&[0, 0x80, 0, 0, 0, 0, 0, 0]), -128.0);
        let full = spec(0, 64, ByteOrder::Intel, true);
        assert_eq!(full.decode(&[0xFF; 8]), -1.0);
    }

    #[test]
    fn encode_refuses_what_does_not_fit() {
        let s = spec(0, 4, ByteOrder::Intel, false);
        let mut d = [0; 8];
        assert!(s.encode(16.0, &mut d).is_err());
        assert!(s.encode(-1.0, &mut d).is_err());
        assert!(s.encode(f64::NAN, &mut d).is_err());
        assert!(s.encode(15.0, &mut d).is_ok());
        let s = spec(0, 4, ByteOrder::Intel, true);
        assert!(s.encode(8.0, &mut d).is_err());
        assert!(s.encode(-8.0, &mut d).is_ok());
        assert_eq!(d[0], 0x08);
    }

    #[test]
    fn bad_layouts_read_zero_and_do_not_fit() {
        let s = spec(60, 8, ByteOrder::Intel, false);
        assert_eq!(s.raw(&[0xFF; 8]), 0);
        assert!(!s.fits(8));
        // MSB at byte 7 bit 1: only 2 bits remain below it.
        assert!(!spec(57, 8, ByteOrder::Motorola, false).fits(8));
        assert!(spec(57, 2, ByteOrder::Motorola, false).fits(8));
        // Byte 0 bits 1..0 then byte 1 bits 7..2.
        assert!(spec(1, 8, ByteOrder::Motorola, false).fits(2));
        assert!(!spec(1, 8, ByteOrder::Motorola, false).fits(1));
        assert!(spec(7, 8, ByteOrder::Motorola, false).fits(1));
        assert!(!spec(15, 8, ByteOrder::Motorola, false).fits(1));
        assert!(!spec(0, 0, ByteOrder::Intel, false).fits(8));
    }
}
