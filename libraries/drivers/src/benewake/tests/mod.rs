//! Tests of the Benewake codec, model rules and driver.

mod codec;
mod decoder;
mod driver;
mod models;
mod props;
mod support;
