//! The RBF's centres binned on a uniform grid, for the near sums of the split
//! evaluation: which centres lie within a radius of a point, without a tree.

use crate::blend::lattice::{cell_of, pack, Fast};
use glam::{DVec3, IVec3};
use std::collections::HashMap;

/// Centre indices by grid bin.
pub(crate) struct CentreBins {
    bin: f64,
    centres: Vec<DVec3>,
    bins: HashMap<u64, Vec<u32>, Fast>,
}

impl CentreBins {
    /// Bins `centres` on a grid of side `bin` (positive). Centres off the
    /// lattice (not finite, or absurdly far) are left out: the RBF would have
    /// refused them.
    pub(crate) fn new(centres: Vec<DVec3>, bin: f64) -> Self {
        let mut bins: HashMap<u64, Vec<u32>, Fast> = HashMap::default();
        for (i, &c) in centres.iter().enumerate() {
            if let Some(cell) = cell_of(c, bin) {
                bins.entry(pack(cell)).or_default().push(i as u32);
            }
        }
        Self { bin, centres, bins }
    }

    /// The centres within `reach` of `q`, in index order; `None` when the
    /// query box leaves the lattice.
    pub(crate) fn within(&self, q: DVec3, reach: f64) -> Option<Vec<u32>> {
        let low = cell_of(q - reach, self.bin)?;
        let high = cell_of(q + reach, self.bin)?;
        let mut found = Vec::new();
        for x in low.x..=high.x {
            for y in low.y..=high.y {
                for z in low.z..=high.z {
                    let Some(bin) = self.bins.get(&pack(IVec3::new(x, y, z))) else {
                        continue;
                    };
                    let close = |i: &&u32| self.centres[**i as usize].distance(q) <= reach;
                    found.extend(bin.iter().filter(close));
                }
            }
        }
        found.sort_unstable();
        Some(found)
    }
}
