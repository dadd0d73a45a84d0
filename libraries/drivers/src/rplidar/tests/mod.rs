//! Tests of the RPLIDAR driver: golden vectors from the protocol and SDK,
//! decoder and state-machine tests, scripted connect transcripts, and
//! property tests (random input, split streams, single-byte mutations).

mod sim;

mod decoders;
mod golden;
mod props;
mod transcript;
