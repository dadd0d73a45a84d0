//! What viewers show, without I/O: the scene model built from surrogates,
//! smooth patches, the arm and its verdicts, and the dashboard's frames and
//! commands.

pub mod dashboard;
pub mod describe;
pub mod scene;
