//! Shared helpers: frames at a time, drivers, clouds.

use crate::assembly::MountPose;
use crate::benewake_can::{
    BenewakeCanConfig, BenewakeCanDriver, BenewakeCanModel, RangefinderConfig,
};
use crate::can::CanFrame;
use crate::can_device::{CanDeviceDriver, CanDriverOutput, FrameClock, SensorCloud, TimedFrame};
use crate::device::HostTime;

pub const EPOCH: u64 = 1_700_000_000_000_000_000;

pub fn host(ms: u64) -> HostTime {
    HostTime::new(ms * 1_000_000, EPOCH + ms * 1_000_000)
}

pub fn at(frame: CanFrame, ms: u64) -> TimedFrame {
    TimedFrame {
        frame,
        stamp_ns: EPOCH + ms * 1_000_000 - 100_000,
        clock: FrameClock::Kernel,
        received: host(ms),
    }
}

pub fn sensor(name: &str, model: BenewakeCanModel, id: u32, mount: MountPose) -> RangefinderConfig {
    RangefinderConfig {
        id,
        ..RangefinderConfig::new(name, model, mount)
    }
}

pub fn driver(sensors: Vec<RangefinderConfig>) -> BenewakeCanDriver {
    let mut d = BenewakeCanDriver::new(BenewakeCanConfig::new(sensors)).unwrap();
    d.connect(host(0), false, &mut Vec::new());
    d
}

/// TF03 / TFmini-i layout: dist cm LE, strength LE (+ u32 ms LE).
pub fn le_frame(id: u32, dist: u16, strength: u16, timestamp: Option<u32>) -> CanFrame {
    let mut bytes = vec![];
    bytes.extend(dist.to_le_bytes());
    bytes.extend(strength.to_le_bytes());
    match timestamp {
        Some(t) => bytes.extend(t.to_le_bytes()),
        None => bytes.extend([0, 0]),
    }
    CanFrame::new(id, false, &bytes).unwrap()
}

/// Legacy TF02: extended id, dist BE, strength BE, exposure, reliability.
pub fn tf02_frame(id: u32, dist: u16, strength: u16, exposure: u8, reliability: u8) -> CanFrame {
    let mut bytes = vec![];
    bytes.extend(dist.to_be_bytes());
    bytes.extend(strength.to_be_bytes());
    bytes.extend([exposure, reliability, 0, 0]);
    CanFrame::new(id, true, &bytes).unwrap()
}

pub fn clouds(out: &[CanDriverOutput]) -> Vec<SensorCloud> {
    out.iter()
        .filter_map(|o| match o {
            CanDriverOutput::Cloud(c) => Some(c.clone()),
            _ => None,
        })
        .collect()
}

pub fn channel<'a>(cloud: &'a SensorCloud, name: &str) -> &'a [f32] {
    &cloud
        .scan
        .channels
        .iter()
        .find(|c| c.name == name)
        .unwrap_or_else(|| panic!("no channel {name}"))
        .values
}

pub fn close(a: f32, b: f32) -> bool {
    (a - b).abs() < 1e-4
}

pub fn receive(d: &mut BenewakeCanDriver, frame: CanFrame, ms: u64) -> Vec<CanDriverOutput> {
    let mut out = Vec::new();
    d.receive(&at(frame, ms), &mut out);
    out
}
