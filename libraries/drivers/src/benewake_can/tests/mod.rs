//! Tests of the Benewake CAN driver: each model's golden frame (bytes by
//! hand from the manuals' tables, sensors.md §2.1), several sensors on one
//! bus, cycles closing by completion, repetition and timeout, invalid
//! readings, repeated timestamps, and random frames.

mod cycles;
mod models;
mod props;
mod support;
