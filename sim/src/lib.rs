//! Test scenes for shroud: seed-deterministic point clouds (`Vec<[f32; 3]>`, xyz) that
//! reproduce the synthetic data of Myles & Peters, "Fast Safe Spline Surrogates for
//! Large Point Clouds" (Section 7: two moving spherical scatter clouds) plus a terrain
//! (smooth hills and sharp cliffs, the Gibbs case) and a table top (boxes and a
//! cylinder, the aliasing case). Every generator validates its parameters and returns
//! a [`SceneError`] instead of panicking.

mod error;
mod moving_spheres;
mod path;
mod sampling;
mod scene;
mod table_objects;
mod table_top;
mod terrain;

pub use error::{SceneError, MAX_POINTS};
pub use moving_spheres::MovingSpheres;
pub use path::LissajousPath;
pub use scene::Scene;
pub use table_objects::{TableBox, TableCylinder};
pub use table_top::TableTop;
pub use terrain::{Cliff, Hill, Terrain};
