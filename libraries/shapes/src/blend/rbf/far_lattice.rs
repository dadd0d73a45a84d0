//! The far field's values at the lattice nodes of the split evaluation (see
//! [`super::split`]), stored in bricks of 4 x 4 x 4 nodes: a 6 x 6 x 6 stencil
//! then meets at most 27 bricks, one hash look-up each, instead of one per node
//! (the look-ups were a fifth of a sampling's time).

use crate::blend::lattice::{pack, Fast};
use glam::IVec3;
use std::collections::HashMap;

/// Nodes per brick side.
const SIDE: i32 = 4;
const VOLUME: usize = (SIDE * SIDE * SIDE) as usize;

/// Not computed yet (far sums of finite weights are finite).
const UNKNOWN: f64 = f64::NAN;
/// Queued for computation by [`FarLattice::missing`].
const PENDING: f64 = f64::INFINITY;

/// Far-field values by lattice node.
#[derive(Default)]
pub(super) struct FarLattice {
    bricks: HashMap<u64, Box<[f64; VOLUME]>, Fast>,
    known: usize,
}

/// Index of `node` within `brick` (which holds it).
#[inline(always)]
fn slot(brick: IVec3, node: IVec3) -> usize {
    let o = node - brick * SIDE;
    (o.x * SIDE * SIDE + o.y * SIDE + o.z) as usize
}

/// Calls `visit(brick, from, to)` for every brick meeting the box
/// `[low, high]` (both inclusive), with the part of the box inside it.
/// (Half-open ranges below: inclusive ones cost an extra test per step.)
#[inline(always)]
fn for_each_brick(low: IVec3, high: IVec3, mut visit: impl FnMut(IVec3, IVec3, IVec3)) {
    let side = IVec3::splat(SIDE);
    let (b0, b1) = (low.div_euclid(side), high.div_euclid(side));
    for bx in b0.x..b1.x + 1 {
        for by in b0.y..b1.y + 1 {
            for bz in b0.z..b1.z + 1 {
                let brick = IVec3::new(bx, by, bz);
                visit(
                    brick,
                    low.max(brick * SIDE),
                    high.min(brick * SIDE + SIDE - 1),
                );
            }
        }
    }
}

impl FarLattice {
    /// Nodes computed so far.
    pub(super) fn len(&self) -> usize {
        self.known
    }

    /// The nodes of the boxes `[cell + low, cell + high]` of `cells` not known
    /// yet, each once; they are marked pending until [`Self::set`].
    pub(super) fn missing(&mut self, cells: &[IVec3], low: i32, high: i32) -> Vec<IVec3> {
        let mut nodes = Vec::new();
        for &cell in cells {
            for_each_brick(cell + low, cell + high, |brick, from, to| {
                let values = self
                    .bricks
                    .entry(pack(brick))
                    .or_insert_with(|| Box::new([UNKNOWN; VOLUME]));
                for x in from.x..to.x + 1 {
                    for y in from.y..to.y + 1 {
                        for z in from.z..to.z + 1 {
                            let node = IVec3::new(x, y, z);
                            let v = &mut values[slot(brick, node)];
                            if v.is_nan() {
                                *v = PENDING;
                                nodes.push(node);
                            }
                        }
                    }
                }
            });
        }
        nodes
    }

    /// Stores computed values (of nodes returned by [`Self::missing`]).
    pub(super) fn set(&mut self, nodes: &[IVec3], values: &[f64]) {
        for (&node, &value) in nodes.iter().zip(values) {
            let brick = node.div_euclid(IVec3::splat(SIDE));
            if let Some(b) = self.bricks.get_mut(&pack(brick)) {
                b[slot(brick, node)] = value;
                self.known += 1;
            }
        }
    }

    /// The values at `cell + offset` for offsets in `low..low + N` per axis
    /// (0 where unknown).
    pub(super) fn stencil<const N: usize>(&self, cell: IVec3, low: i32) -> [[[f64; N]; N]; N] {
        let mut out = [[[0.0; N]; N]; N];
        let origin = cell + low;
        for_each_brick(origin, origin + (N as i32 - 1), |brick, from, to| {
            let Some(values) = self.bricks.get(&pack(brick)) else {
                return;
            };
            for x in from.x..to.x + 1 {
                for y in from.y..to.y + 1 {
                    for z in from.z..to.z + 1 {
                        let node = IVec3::new(x, y, z);
                        let v = values[slot(brick, node)];
                        let o = node - origin;
                        out[o.x as usize][o.y as usize][o.z as usize] =
                            if v.is_finite() { v } else { 0.0 };
                    }
                }
            }
        });
        out
    }
}
