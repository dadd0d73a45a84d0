//! Foot points on a multipatch surface: the parameters of the surface point
//! nearest to a data point, by Gauss-Newton steps that carry on into the
//! neighbouring patch when they leave the unit square. This is the parameter
//! correction of paper 004 (Section 6, after Hoschek [14]): without crossing
//! borders, points near an edge would stay pinned to the wrong patch.

use super::sample::Sample;
use crate::mesh::QuadMesh;
use glam::DVec3;

/// A surface made of patches over the unit square, with first derivatives.
pub trait PatchSurface: Sync {
    /// The point and its partial derivatives in u and v on `face` at (u, v).
    fn jet(&self, face: usize, u: f64, v: f64) -> [DVec3; 3];
}

/// Which patch lies across each side of each patch, and which of its sides
/// it is. Side k runs from corner k to corner k + 1 (corners at (0,0),
/// (1,0), (1,1), (0,1)), i.e. half-edge `4 face + k`.
#[derive(Debug, Clone)]
pub struct PatchAdjacency {
    across: Vec<[Option<(usize, usize)>; 4]>,
}

impl PatchAdjacency {
    pub fn new(mesh: &QuadMesh) -> Self {
        let he = mesh.half_edges();
        let across = (0..mesh.face_count())
            .map(|f| [0, 1, 2, 3].map(|k| he.opposite(4 * f + k).map(|o| (he.face(o), o % 4))))
            .collect();
        Self { across }
    }

    /// `(face, u, v)` with (u, v) possibly outside the unit square, moved into
    /// the patch that contains it: across the side it left by most, keeping
    /// the position along the shared edge and the depth past it (exact where
    /// the patches meet C1, first order at extraordinary edges). At the
    /// domain's boundary the parameters are clamped.
    pub fn wrap(&self, face: usize, u: f64, v: f64) -> Sample {
        let (mut face, mut u, mut v) = (face, u, v);
        // A corner crossing takes two moves; four bound the walk round an EV.
        for _ in 0..4 {
            let outside = [-v, u - 1.0, v - 1.0, -u];
            let (side, depth) = outside
                .iter()
                .copied()
                .enumerate()
                .fold((0, f64::NEG_INFINITY), |a, b| if b.1 > a.1 { b } else { a });
            if depth <= 0.0 {
                break;
            }
            let Some((next, next_side)) = self.across[face][side] else {
                break;
            };
            let along = along_side(side, u, v);
            (u, v) = from_side(next_side, 1.0 - along, depth);
            face = next;
        }
        Sample {
            face,
            u: u.clamp(0.0, 1.0),
            v: v.clamp(0.0, 1.0),
        }
    }
}

/// Position along side k, from corner k toward corner k + 1.
fn along_side(side: usize, u: f64, v: f64) -> f64 {
    match side {
        0 => u,
        1 => v,
        2 => 1.0 - u,
        _ => 1.0 - v,
    }
}

/// The parameters at `along` on side k, `depth` into the patch.
fn from_side(side: usize, along: f64, depth: f64) -> (f64, f64) {
    match side {
        0 => (along, depth),
        1 => (1.0 - depth, along),
        2 => (1.0 - along, 1.0 - depth),
        _ => (depth, 1.0 - along),
    }
}

/// The foot point of `p` from `start`: at most `iterations` Gauss-Newton
/// steps on |S(u, v) - p|^2, each no longer than half a patch, each crossing
/// into the neighbour when it leaves the patch, and each halved until it
/// brings the surface closer (a few times at most). Returns the parameters
/// and the distance.
pub fn foot_point(
    surface: &impl PatchSurface,
    adjacency: &PatchAdjacency,
    start: Sample,
    p: DVec3,
    iterations: usize,
) -> (Sample, f64) {
    let mut at = start;
    let mut jet = surface.jet(at.face, at.u, at.v);
    let mut dist = (jet[0] - p).length();
    for _ in 0..iterations {
        let Some((du, dv)) = gauss_newton_step(jet, p) else {
            break;
        };
        let Some((next, next_jet, d)) = first_closer(surface, adjacency, at, (du, dv), p, dist)
        else {
            break;
        };
        let converged =
            next.face == at.face && (next.u - at.u).abs() + (next.v - at.v).abs() < 1e-10;
        (at, jet, dist) = (next, next_jet, d);
        if converged {
            break;
        }
    }
    (at, dist)
}

/// The Gauss-Newton step toward the foot point of `p`, at most half a patch
/// long; `None` where the surface is singular.
fn gauss_newton_step([s, su, sv]: [DVec3; 3], p: DVec3) -> Option<(f64, f64)> {
    let r = p - s;
    let (a, b, c) = (su.dot(su), su.dot(sv), sv.dot(sv));
    let det = a * c - b * b;
    if det.is_nan() || det <= 1e-300 {
        return None;
    }
    let (gu, gv) = (r.dot(su), r.dot(sv));
    let (du, dv) = ((c * gu - b * gv) / det, (a * gv - b * gu) / det);
    let scale = (0.5 / du.abs().max(dv.abs())).min(1.0);
    (du.is_finite() && dv.is_finite()).then_some((du * scale, dv * scale))
}

/// The step, halved up to six times, that first lands closer than `dist`.
fn first_closer(
    surface: &impl PatchSurface,
    adjacency: &PatchAdjacency,
    at: Sample,
    (du, dv): (f64, f64),
    p: DVec3,
    dist: f64,
) -> Option<(Sample, [DVec3; 3], f64)> {
    let mut t = 1.0;
    for _ in 0..7 {
        let next = adjacency.wrap(at.face, at.u + t * du, at.v + t * dv);
        let jet = surface.jet(next.face, next.u, next.v);
        let d = (jet[0] - p).length();
        if d < dist {
            return Some((next, jet, d));
        }
        t *= 0.5;
    }
    None
}

/// The bilinear patches of a quad mesh's faces: the initial parametrisation
/// of points near a 3D domain mesh.
#[derive(Debug, Clone)]
pub struct BilinearPatches {
    quads: Vec<[DVec3; 4]>,
}

impl BilinearPatches {
    pub fn new(mesh: &QuadMesh) -> Self {
        let v = mesh.vertices();
        let quads = mesh
            .faces()
            .iter()
            .map(|f| f.map(|i| DVec3::from_array(v[i as usize])))
            .collect();
        Self { quads }
    }
}

impl PatchSurface for BilinearPatches {
    fn jet(&self, face: usize, u: f64, v: f64) -> [DVec3; 3] {
        let [a, b, c, d] = self.quads[face];
        let point =
            a * ((1.0 - u) * (1.0 - v)) + b * (u * (1.0 - v)) + c * (u * v) + d * ((1.0 - u) * v);
        let du = (b - a) * (1.0 - v) + (c - d) * v;
        let dv = (d - a) * (1.0 - u) + (c - b) * u;
        [point, du, dv]
    }
}
