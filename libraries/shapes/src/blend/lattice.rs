//! Integer lattice points packed into `u64` keys, and a cheap hasher for them:
//! the sparse grids of the zero-set sampler and of the RBF's far field.

use glam::IVec3;
use std::hash::{BuildHasherDefault, Hasher};

/// Each coordinate of a packed lattice point lies strictly within +-2^19 (the
/// packing holds +-2^20; the margin leaves room for a cell's neighbours).
pub(crate) const LATTICE_LIMIT: f64 = (1 << 19) as f64;

/// A cheap multiplicative hasher for packed lattice keys.
#[derive(Default)]
pub(crate) struct LatticeHasher(u64);

impl Hasher for LatticeHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x100_0000_01b3);
        }
    }
    fn write_u64(&mut self, x: u64) {
        self.0 = (x ^ (x >> 29)).wrapping_mul(0x9e37_79b9_7f4a_7c15);
        self.0 ^= self.0 >> 32;
    }
}

pub(crate) type Fast = BuildHasherDefault<LatticeHasher>;

/// Packs a lattice point (each coordinate within +-2^20) into a u64.
pub(crate) fn pack(v: IVec3) -> u64 {
    let f = |c: i32| (c as i64 + (1 << 20)) as u64 & 0x1f_ffff;
    f(v.x) | f(v.y) << 21 | f(v.z) << 42
}

/// The lattice cell of spacing `step` (anchored at the origin) holding `q`, if
/// `q` is finite and within [`LATTICE_LIMIT`] cells of the origin.
pub(crate) fn cell_of(q: glam::DVec3, step: f64) -> Option<IVec3> {
    let g = (q / step).floor();
    (g.is_finite() && g.abs().max_element() < LATTICE_LIMIT).then(|| g.as_ivec3())
}
