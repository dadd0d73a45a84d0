//! Test scenes for shroud: seed-deterministic point clouds (`Vec<[f32; 3]>`, xyz) that
//! reproduce the synthetic data of Myles & Peters, "Fast Safe Spline Surrogates for
//! Large Point Clouds" (Section 7: two moving spherical scatter clouds) plus a terrain
//! (smooth hills and sharp cliffs, the Gibbs case) and a table top (boxes and a
//! cylinder, the aliasing case). Every generator validates its parameters and returns
//! a [`SceneError`] instead of panicking. [`Crossing`] walks a person across a
//! cell, the scene of the speed and separation monitoring demo.
//!
//! The scan scenes put a simulated [`RangeScanner`] (rays cast through a [`Bvh`]
//! of a triangle mesh, with range noise and dropouts) around the table-top and
//! terrain meshes ([`TableTop::mesh`], [`Terrain::mesh`]) or any user mesh.
//!
//! [`soundness`] is a brute-force check of the collision guard: random scenes
//! of moving solids, scanned, fitted and judged by shroud, every verdict
//! compared with exact geometry of its own.

mod crossing;
mod error;
mod mesh_scene;
mod moving_spheres;
pub mod parts;
mod path;
mod sampling;
pub mod scanned_parts;
mod scanner;
mod scene;
pub mod soundness;
mod table_objects;
mod table_top;
mod terrain;
pub mod world;

pub use crossing::Crossing;
pub use error::{SceneError, MAX_POINTS};
pub use mesh_scene::{DEFAULT_CYLINDER_SEGMENTS, DEFAULT_TERRAIN_CELLS, MAX_CYLINDER_SEGMENTS};
pub use moving_spheres::{Floor, MovingSpheres};
pub use path::LissajousPath;
pub use scanner::{
    Bvh, MeshScan, RangeScanner, RayHit, ScanFrame, ScanPose, ScanResolution, SensorPose,
    TableTopScan, TerrainScan,
};
pub use scene::Scene;
pub use table_objects::{TableBox, TableCylinder};
pub use table_top::TableTop;
pub use terrain::{Cliff, Hill, Terrain};
