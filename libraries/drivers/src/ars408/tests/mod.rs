//! Tests of the ARS408 driver: golden frames computed by hand (sensors.md
//! §2.2 layouts, packed by an encoder written here, independent of the DBC
//! module), cycle assembly and its losses, configuration, health, objects,
//! mounts, and random input.

mod clusters;
mod configuration;
mod objects;
mod props;
mod support;
