//! Initial parameters of points around a domain mesh in space (a parametric
//! fit of a scanned object over its coarse quad mesh): the foot point on a
//! close polyhedral stand-in for the mesh's smooth Catmull-Clark limit surface
//! (the mesh refined a few times, vertices at their limit positions), started
//! from the faces whose centres are nearest, and taken back to the domain's
//! faces. Projecting onto the coarse faces themselves would pile the points
//! of a curved object onto the faces' edges, a distortion that parameter
//! correction then removes only slowly.

use super::foot_point::{foot_point, BilinearPatches, PatchAdjacency, PatchSurface};
use super::sample::Sample;
use crate::mesh::{
    coarsen_parameters, levels_within, limit_position, refine_mesh, MeshError, QuadMesh,
};
use glam::DVec3;
use shroud_geometry::cloud::NeighbourIndex;

/// Starts tried per point: the foot point from the nearest centre can stop
/// at a patch border where the mesh folds; a few more starts settle it.
const STARTS: usize = 3;

/// Refinements of the stand-in surface, fewer on meshes already fine.
const MAX_LEVELS: usize = 3;
const MAX_STAND_IN_FACES: usize = 1 << 18;

/// Locates points near a quad mesh in space.
#[derive(Debug)]
pub struct SurfaceLocator {
    patches: BilinearPatches,
    adjacency: PatchAdjacency,
    centres: NeighbourIndex,
    levels: usize,
}

impl SurfaceLocator {
    pub fn new(mesh: &QuadMesh) -> Result<Self, MeshError> {
        let levels = levels_within(mesh, MAX_LEVELS, MAX_STAND_IN_FACES);
        let fine = refine_mesh(mesh, levels)?;
        let limit = (0..fine.vertex_count())
            .map(|v| limit_position(&fine, v))
            .collect();
        let (_, faces) = fine.into_parts();
        let stand_in = QuadMesh::new(limit, faces)?;
        let patches = BilinearPatches::new(&stand_in);
        let centres = (0..stand_in.face_count())
            .map(|f| patches.jet(f, 0.5, 0.5)[0])
            .collect();
        Ok(Self {
            patches,
            adjacency: PatchAdjacency::new(&stand_in),
            centres: NeighbourIndex::new(centres),
            levels,
        })
    }

    /// The parameters of the point of the mesh nearest to `p`, `None` when `p`
    /// is not finite.
    pub fn locate(&self, p: [f64; 3]) -> Option<Sample> {
        let p = DVec3::from_array(p);
        if !p.is_finite() {
            return None;
        }
        self.centres
            .nearest(p, STARTS)
            .into_iter()
            .map(|(face, _)| {
                let start = Sample {
                    face,
                    u: 0.5,
                    v: 0.5,
                };
                foot_point(&self.patches, &self.adjacency, start, p, 30)
            })
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(s, _)| {
                let (face, u, v) = coarsen_parameters(s.face, s.u, s.v, self.levels);
                Sample { face, u, v }
            })
    }
}
