//! The contract between a CAN device driver (pure, here) and the node that
//! owns the bus (frames and time, in `nodes`).

use super::super::can::CanFrame;
use super::super::device::{DeviceState, DeviceStats, HostTime};
use super::super::Scan;
use super::timed_frame::TimedFrame;

/// A cloud assembled from one measurement cycle, points already in the
/// robot's frame (the driver applies its mounts).
#[derive(Debug, Clone, PartialEq)]
pub struct SensorCloud {
    /// `stamp_ns` is the stamp of the cycle's first frame; `channels` carry
    /// what the device measures beside position (radar velocities, RCS).
    pub scan: Scan,
    /// When the cycle's first frame was read on this host: the cloud's age
    /// counts from here, so it is never younger than its oldest data.
    pub received: HostTime,
}

/// What a CAN driver asks of its bus, or reports to its node, in order.
#[derive(Debug, Clone, PartialEq)]
pub enum CanDriverOutput {
    /// Send this frame (configuration). A read-only transport (a log replay)
    /// counts it as unsent.
    Send(CanFrame),
    /// A complete cycle's cloud.
    Cloud(SensorCloud),
    /// The driver changed state.
    State(DeviceState),
    /// What the device says it is, as `key = value` pairs.
    Identity(Vec<(String, String)>),
    /// The device's own health report (ARS408 RadarState error bits).
    Health { ok: bool, detail: String },
}

/// A CAN sensor's driver. The node calls [`connect`](Self::connect) each time
/// the bus opens, [`receive`](Self::receive) with every frame (every frame of
/// the bus: the driver counts and ignores other devices' ids),
/// [`poll`](Self::poll) whenever nothing arrives (at least every 100 ms) and
/// after each `receive`, and [`disconnect`](Self::disconnect) when the bus
/// goes away. Drivers never block, never read a clock and never panic on
/// any frame.
pub trait CanDeviceDriver: Send {
    /// The device kind (`ars408`, `benewake_can`).
    fn kind(&self) -> &'static str;
    /// The bus has just been opened (the first time or after a reconnect):
    /// forget partial cycles and start configuring. `writable` is false on a
    /// log replay: nothing sent would arrive.
    fn connect(&mut self, now: HostTime, writable: bool, out: &mut Vec<CanDriverOutput>);
    /// One received frame.
    fn receive(&mut self, frame: &TimedFrame, out: &mut Vec<CanDriverOutput>);
    /// Time-driven decisions: configuration retries, a silent device.
    fn poll(&mut self, now: HostTime, out: &mut Vec<CanDriverOutput>);
    /// The bus went away: drop partial cycles (counted).
    fn disconnect(&mut self, out: &mut Vec<CanDriverOutput>);
    /// The current state.
    fn state(&self) -> &DeviceState;
    /// The counters so far (kept across reconnects).
    fn stats(&self) -> &DeviceStats;
    /// Counters beyond [`DeviceStats`]' kinds, by name (a rangefinder
    /// array's missing readings per sensor, `missing_reading.<name>`).
    fn named_counters(&self) -> Vec<(String, u64)> {
        Vec::new()
    }
}
