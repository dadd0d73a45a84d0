//! Tests of the queries against hand-made and fitted surrogates.

pub mod fixtures;

mod bound;
mod classify;
mod ray;
mod throughput;
mod view;
