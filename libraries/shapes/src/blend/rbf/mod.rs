//! The transition surface's implicit function (Zou et al., Section 5, Eq. 1): the
//! triharmonic RBF `s(x) = p(x) + sum_i lambda_i |x - x_i|^3` with a linear
//! polynomial `p`, fitted to on- and off-surface constraints (Carr et al. 2001), with
//! greedy centre reduction and a dense solve; evaluated at many points either
//! directly or split into near sums and an interpolated far field.

mod batch;
mod centre_bins;
mod constraints;
mod eval;
mod far_lattice;
mod greedy;
mod grow;
mod near_sum;
mod projection;
mod solve;
mod split;
mod split_kernel;
#[cfg(test)]
mod split_props;

pub use batch::{BatchField, ExactField};
pub use constraints::{build_constraints, Constraints};
pub use eval::Rbf;
pub use greedy::{fit_greedy, GreedyReport, RbfParams};
pub use split::SplitField;
