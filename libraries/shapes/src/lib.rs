//! Shapes beyond one surrogate: quad meshes and their subdivision, blending a
//! child surface into a parent (paper 001), G1 smooth fitting over a quad
//! domain (paper 004), and one reader and writer per file format.

pub mod blend;
pub mod format;
pub mod mesh;
pub mod smooth;
