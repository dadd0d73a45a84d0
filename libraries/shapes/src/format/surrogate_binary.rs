//! The compact binary surrogate format (`.shrd`). All numbers little endian;
//! `f64` are IEEE 754 binary64 stored bit for bit.
//!
//! | size (bytes)        | field                                                   |
//! |---------------------|---------------------------------------------------------|
//! | 8                   | magic `SHRDSURR`                                        |
//! | 4                   | `u32` version, 1                                        |
//! | 96                  | frame: `direction`, `u`, `v`, `w`, each 3 `f64` (x, y, z) |
//! | 32                  | domain: `u_min`, `v_min`, `u_step`, `v_step` (`f64`)   |
//! | 8                   | domain: `cols`, `rows` (`u32`)                          |
//! | 1                   | surface flags: bit 0 upper present, bit 1 lower present |
//! | 8                   | trim: `cells_s`, `cells_t` (`u32`)                       |
//! | cells_s * cells_t   | trim bits, one byte per cell, row-major `[g * cells_s + h]` |
//! |                     | then for each present surface, upper first:             |
//! | 1                   | side: 0 upper, 1 lower                                  |
//! | 8                   | `cols`, `rows` (`u32`)                                  |
//! | 8 * cols * rows     | coefficients (`f64`), row-major `b[k * cols + j]`        |
//! | 24                  | certificate `direction`, 3 `f64`                         |
//! | 16                  | certificate `points_checked`, `violations` (`u64`)       |
//! | 24                  | certificate `min_gap`, `max_gap`, `mean_gap` (`f64`)     |
//! | 8                   | certificate `corrected_points` (`u64`)                   |
//! |                     | and last:                                               |
//! | 4                   | `u32` CRC-32 (IEEE) of every byte before it              |
//!
//! The certificate's side is the surface's side and is not stored again. The fit
//! statistics ([`shroud_surrogate::FitStats`]) are not stored: a loaded surrogate
//! has default (zero) statistics. Reading checks the magic, version, lengths,
//! checksum and then every invariant of `docs/formats.md` ("Validation").

use super::crc32::crc32;
use super::FormatError;
use glam::DVec3;
use shroud_geometry::math::Frame;
use shroud_geometry::spline::UniformCubicSurface;
use shroud_surrogate::validate_surrogate;
use shroud_surrogate::{Certificate, Domain, FitStats, SafeSurface, Side, Surrogate, TrimMask};

/// The first 8 bytes of every binary surrogate.
pub const SURROGATE_MAGIC: &[u8; 8] = b"SHRDSURR";
/// The version this build writes and reads.
pub const SURROGATE_BINARY_VERSION: u32 = 1;

const UPPER_PRESENT: u8 = 1;
const LOWER_PRESENT: u8 = 2;

/// The surrogate in the binary format (statistics left out).
pub fn surrogate_to_binary(surrogate: &Surrogate) -> Vec<u8> {
    let mut out = Writer::default();
    out.bytes(SURROGATE_MAGIC);
    out.u32(SURROGATE_BINARY_VERSION);
    let frame = &surrogate.frame;
    [frame.direction, frame.u, frame.v, frame.w]
        .iter()
        .for_each(|a| out.vec3(a.to_array()));
    let d = &surrogate.domain;
    [d.u_min, d.v_min, d.u_step, d.v_step]
        .iter()
        .for_each(|&x| out.f64(x));
    out.len(d.cols);
    out.len(d.rows);
    let flags = if surrogate.upper.is_some() {
        UPPER_PRESENT
    } else {
        0
    } | if surrogate.lower.is_some() {
        LOWER_PRESENT
    } else {
        0
    };
    out.bytes(&[flags]);
    out.len(surrogate.trim.cells_s);
    out.len(surrogate.trim.cells_t);
    out.bytes(&surrogate.trim.bits);
    for safe in surrogate.surfaces() {
        write_surface(&mut out, safe);
    }
    let checksum = crc32(&out.0);
    out.u32(checksum);
    out.0
}

fn write_surface(out: &mut Writer, safe: &SafeSurface) {
    out.bytes(&[side_code(safe.side)]);
    out.len(safe.surface.cols);
    out.len(safe.surface.rows);
    safe.surface.coefficients.iter().for_each(|&c| out.f64(c));
    let c = &safe.certificate;
    out.vec3(c.direction);
    out.u64(c.points_checked);
    out.u64(c.violations);
    [c.min_gap, c.max_gap, c.mean_gap]
        .iter()
        .for_each(|&x| out.f64(x));
    out.u64(c.corrected_points);
}

fn side_code(side: Side) -> u8 {
    match side {
        Side::Upper => 0,
        Side::Lower => 1,
    }
}

/// Reads and validates a binary surrogate.
pub fn surrogate_from_binary(bytes: &[u8]) -> Result<Surrogate, FormatError> {
    let mut r = Reader { bytes, pos: 0 };
    if r.take(8, "magic")? != SURROGATE_MAGIC {
        return Err(FormatError::BadMagic);
    }
    let version = r.u32("version")?;
    if version != SURROGATE_BINARY_VERSION {
        return Err(FormatError::UnsupportedVersion {
            found: version.into(),
            supported: SURROGATE_BINARY_VERSION,
        });
    }
    let frame = Frame {
        direction: r.vec3("frame")?,
        u: r.vec3("frame")?,
        v: r.vec3("frame")?,
        w: r.vec3("frame")?,
    };
    let domain = read_domain(&mut r)?;
    let flags_at = r.pos;
    let flags = r.u8("surface flags")?;
    if flags & !(UPPER_PRESENT | LOWER_PRESENT) != 0 {
        return Err(FormatError::BadField {
            what: "surface flags",
            offset: flags_at,
            value: flags.into(),
        });
    }
    let trim = read_trim(&mut r)?;
    let upper = (flags & UPPER_PRESENT != 0)
        .then(|| read_surface(&mut r, Side::Upper))
        .transpose()?;
    let lower = (flags & LOWER_PRESENT != 0)
        .then(|| read_surface(&mut r, Side::Lower))
        .transpose()?;
    let covered = r.pos;
    let stored = r.u32("checksum")?;
    if r.pos < bytes.len() {
        return Err(FormatError::TrailingBytes {
            count: bytes.len() - r.pos,
        });
    }
    let computed = crc32(&bytes[..covered]);
    if stored != computed {
        return Err(FormatError::ChecksumMismatch { stored, computed });
    }
    let surrogate = Surrogate {
        frame,
        domain,
        trim,
        upper,
        lower,
        stats: FitStats::default(),
    };
    validate_surrogate(&surrogate)?;
    Ok(surrogate)
}

fn read_domain(r: &mut Reader) -> Result<Domain, FormatError> {
    Ok(Domain {
        u_min: r.f64("domain")?,
        v_min: r.f64("domain")?,
        u_step: r.f64("domain")?,
        v_step: r.f64("domain")?,
        cols: r.u32("domain cols")? as usize,
        rows: r.u32("domain rows")? as usize,
    })
}

fn read_trim(r: &mut Reader) -> Result<TrimMask, FormatError> {
    let cells_s = r.u32("trim cells_s")?;
    let cells_t = r.u32("trim cells_t")?;
    let bits = r
        .take(u64::from(cells_s) * u64::from(cells_t), "trim bits")?
        .to_vec();
    Ok(TrimMask {
        cells_s: cells_s as usize,
        cells_t: cells_t as usize,
        bits,
    })
}

fn read_surface(r: &mut Reader, side: Side) -> Result<SafeSurface, FormatError> {
    let side_at = r.pos;
    let code = r.u8("surface side")?;
    if code != side_code(side) {
        return Err(FormatError::BadField {
            what: "surface side",
            offset: side_at,
            value: code.into(),
        });
    }
    let cols = r.u32("surface cols")?;
    let rows = r.u32("surface rows")?;
    let count = u64::from(cols) * u64::from(rows);
    let data = r.take(count.saturating_mul(8), "coefficients")?;
    let coefficients = data.chunks_exact(8).map(f64_of).collect();
    let surface = UniformCubicSurface {
        cols: cols as usize,
        rows: rows as usize,
        coefficients,
    };
    let certificate = Certificate {
        side,
        direction: r.vec3("certificate")?.to_array(),
        points_checked: r.u64("certificate")?,
        violations: r.u64("certificate")?,
        min_gap: r.f64("certificate")?,
        max_gap: r.f64("certificate")?,
        mean_gap: r.f64("certificate")?,
        corrected_points: r.u64("certificate")?,
    };
    Ok(SafeSurface {
        side,
        surface,
        certificate,
    })
}

/// An f64 from 8 little-endian bytes (`chunks_exact(8)` guarantees the length).
fn f64_of(bytes: &[u8]) -> f64 {
    let mut array = [0u8; 8];
    array.copy_from_slice(bytes);
    f64::from_le_bytes(array)
}

#[derive(Default)]
struct Writer(Vec<u8>);

impl Writer {
    fn bytes(&mut self, b: &[u8]) {
        self.0.extend_from_slice(b);
    }
    fn u32(&mut self, x: u32) {
        self.bytes(&x.to_le_bytes());
    }
    /// A size as `u32`; sizes that do not fit (never valid) become `u32::MAX`,
    /// which the reader rejects.
    fn len(&mut self, x: usize) {
        self.u32(u32::try_from(x).unwrap_or(u32::MAX));
    }
    fn u64(&mut self, x: u64) {
        self.bytes(&x.to_le_bytes());
    }
    fn f64(&mut self, x: f64) {
        self.bytes(&x.to_le_bytes());
    }
    fn vec3(&mut self, v: [f64; 3]) {
        v.iter().for_each(|&x| self.f64(x));
    }
}

/// A cursor that reports what it was reading when the bytes run out.
struct Reader<'a> {
    bytes: &'a [u8],
    pos: usize,
}

impl<'a> Reader<'a> {
    fn take(&mut self, needed: u64, what: &'static str) -> Result<&'a [u8], FormatError> {
        let available = self.bytes.len() - self.pos;
        let truncated = FormatError::Truncated {
            what,
            offset: self.pos,
            needed,
            available,
        };
        let n = usize::try_from(needed).map_err(|_| truncated.clone())?;
        if n > available {
            return Err(truncated);
        }
        let slice = &self.bytes[self.pos..self.pos + n];
        self.pos += n;
        Ok(slice)
    }
    fn array<const N: usize>(&mut self, what: &'static str) -> Result<[u8; N], FormatError> {
        let mut array = [0u8; N];
        array.copy_from_slice(self.take(N as u64, what)?);
        Ok(array)
    }
    fn u8(&mut self, what: &'static str) -> Result<u8, FormatError> {
        Ok(self.array::<1>(what)?[0])
    }
    fn u32(&mut self, what: &'static str) -> Result<u32, FormatError> {
        Ok(u32::from_le_bytes(self.array(what)?))
    }
    fn u64(&mut self, what: &'static str) -> Result<u64, FormatError> {
        Ok(u64::from_le_bytes(self.array(what)?))
    }
    fn f64(&mut self, what: &'static str) -> Result<f64, FormatError> {
        Ok(f64::from_le_bytes(self.array(what)?))
    }
    fn vec3(&mut self, what: &'static str) -> Result<DVec3, FormatError> {
        Ok(DVec3::new(
            self.f64(what)?,
            self.f64(what)?,
            self.f64(what)?,
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::format::SurrogateDefect;
    use shroud_surrogate::samples::fitted;
    use shroud_surrogate::Sides;

    fn without_stats(mut s: Surrogate) -> Surrogate {
        s.stats = FitStats::default();
        s
    }

    #[test]
    fn round_trip_is_exact_except_statistics() {
        for sides in [Sides::Upper, Sides::Lower, Sides::Sandwich] {
            let surrogate = fitted(sides, true);
            let back = surrogate_from_binary(&surrogate_to_binary(&surrogate)).unwrap();
            assert_eq!(back, without_stats(surrogate.clone()));
            for (a, b) in back.surfaces().zip(surrogate.surfaces()) {
                let bits = |s: &SafeSurface| {
                    s.surface
                        .coefficients
                        .iter()
                        .map(|c| c.to_bits())
                        .collect::<Vec<_>>()
                };
                assert_eq!(bits(a), bits(b));
            }
        }
    }

    #[test]
    fn size_follows_the_documented_layout() {
        let surrogate = fitted(Sides::Sandwich, true);
        let cells = surrogate.trim.bits.len();
        let surface = 1 + 8 + 8 * 30 + 72;
        assert_eq!(
            surrogate_to_binary(&surrogate).len(),
            8 + 4 + 96 + 40 + 1 + 8 + cells + 2 * surface + 4
        );
        let bytes = surrogate_to_binary(&surrogate);
        assert_eq!(&bytes[..8], b"SHRDSURR");
        assert_eq!(bytes[148], UPPER_PRESENT | LOWER_PRESENT);
        let crc_at = bytes.len() - 4;
        assert_eq!(
            u32::from_le_bytes(bytes[crc_at..].try_into().unwrap()),
            crc32(&bytes[..crc_at])
        );
    }

    #[test]
    fn every_truncation_is_an_error() {
        let bytes = surrogate_to_binary(&fitted(Sides::Sandwich, true));
        for len in 0..bytes.len() {
            assert!(
                matches!(
                    surrogate_from_binary(&bytes[..len]),
                    Err(FormatError::Truncated { .. })
                ),
                "cut at {len}"
            );
        }
    }

    #[test]
    fn every_corrupted_byte_is_an_error() {
        let bytes = surrogate_to_binary(&fitted(Sides::Upper, true));
        for at in 0..bytes.len() {
            for flip in [0x01, 0x80, 0xff] {
                let mut corrupted = bytes.clone();
                corrupted[at] ^= flip;
                assert!(
                    surrogate_from_binary(&corrupted).is_err(),
                    "byte {at} ^ {flip:#x}"
                );
            }
        }
        // A coefficient bit flip keeps the structure: only the checksum can tell.
        let mut corrupted = bytes.clone();
        corrupted[8 + 4 + 96 + 40 + 1 + 8 + 20 + 9 + 3] ^= 0x10;
        assert!(matches!(
            surrogate_from_binary(&corrupted),
            Err(FormatError::ChecksumMismatch { .. })
        ));
    }

    #[test]
    fn header_and_trailer_errors_are_named() {
        let bytes = surrogate_to_binary(&fitted(Sides::Upper, true));
        let mut extra = bytes.clone();
        extra.extend_from_slice(b"xy");
        assert_eq!(
            surrogate_from_binary(&extra),
            Err(FormatError::TrailingBytes { count: 2 })
        );
        let mut magic = bytes.clone();
        magic[0] = b'X';
        assert_eq!(surrogate_from_binary(&magic), Err(FormatError::BadMagic));
        let mut version = bytes.clone();
        version[8] = 9;
        assert_eq!(
            surrogate_from_binary(&version),
            Err(FormatError::UnsupportedVersion {
                found: 9,
                supported: 1
            })
        );
        // An absurd trim size is caught before any allocation.
        let mut huge = bytes.clone();
        huge[149..157].copy_from_slice(&[0xff; 8]);
        assert!(matches!(
            surrogate_from_binary(&huge),
            Err(FormatError::Truncated {
                what: "trim bits",
                ..
            })
        ));
    }

    #[test]
    fn loaded_files_are_validated() {
        let mut surrogate = fitted(Sides::Upper, true);
        surrogate.domain.u_step = -1.0;
        assert!(matches!(
            surrogate_from_binary(&surrogate_to_binary(&surrogate)),
            Err(FormatError::InvalidSurrogate(SurrogateDefect::Domain {
                field: "u_step",
                ..
            }))
        ));
    }
}
