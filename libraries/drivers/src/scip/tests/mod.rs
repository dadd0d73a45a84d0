//! Tests of the SCIP 2.0 codec pieces, clock and driver: golden vectors from
//! the spec, scripted handshake transcripts, state-machine tests and property
//! tests.

mod clock;
mod codec;
mod multiecho;
mod multiecho_props;
mod props;
mod stream;
mod support;
mod transcripts;
