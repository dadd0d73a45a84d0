//! Command-line option groups that a CLI subcommand and a node share, in one
//! place so that neither imports the other.

mod blend;
mod smooth;
mod surrogate;

pub use blend::{points3, BlendShapeArgs};
pub use smooth::{DomainKind, SmoothDomainArgs};
pub use surrogate::SurrogateShapeArgs;
