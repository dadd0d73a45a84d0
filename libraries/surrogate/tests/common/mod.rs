//! Helpers shared by the integration tests: adversarial clouds, fitting
//! directions, and the brute-force check of the safety guarantee.
// Each test crate uses a different subset of these helpers.
#![allow(dead_code)]

pub mod brute_force;
pub mod clouds;
pub mod config;
pub mod directions;
pub mod exact;
