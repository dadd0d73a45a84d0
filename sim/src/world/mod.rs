//! The world an emulated sensor measures, shared by the serial and the CAN
//! emulators (`shroud_emulators`): a ray's first return ([`RaySource`]), and
//! the rays of a (moving) mount into a triangle mesh ([`MeshRays`]).

mod mesh_rays;
mod ray;

pub use mesh_rays::MeshRays;
pub use ray::{RayReturn, RaySource};
