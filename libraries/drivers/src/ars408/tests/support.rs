//! Frame builders for the tests: the radar's messages packed bit by bit from
//! the research note's `start|len` table (Motorola: start = MSB position),
//! not through the DBC module under test.

use crate::ars408::{Ars408Config, Ars408Driver};
use crate::can::CanFrame;
use crate::can_device::{CanDeviceDriver, CanDriverOutput, FrameClock, SensorCloud, TimedFrame};
use crate::dbc::builtin;
use crate::device::HostTime;

/// Puts `raw` into `data` as a Motorola signal whose MSB is bit `start`
/// (DBC sawtooth numbering: bit 7 of byte 0 is 7, then 6..0, then 15 ...).
pub fn put(data: &mut [u8; 8], start: u32, len: u32, raw: u64) {
    let mut pos = start;
    for i in 0..len {
        let bit = (raw >> (len - 1 - i)) & 1;
        let (byte, shift) = ((pos / 8) as usize, pos % 8);
        if bit == 1 {
            data[byte] |= 1 << shift;
        }
        // Next lower bit: down within the byte, then to bit 7 of the next byte.
        pos = if shift == 0 { pos + 15 } else { pos - 1 };
    }
}

/// The raw value of a physical one: (value - offset) / factor.
pub fn raw(value: f64, factor: f64, offset: f64) -> u64 {
    ((value - offset) / factor).round() as u64
}

pub fn frame(id: u32, len: usize, data: [u8; 8]) -> CanFrame {
    CanFrame::new(id, false, &data[..len]).unwrap()
}

/// 0x600 + offset: near, far, MeasCounter.
pub fn cluster_status(base: u32, near: u64, far: u64, counter: u64) -> CanFrame {
    let mut d = [0; 8];
    put(&mut d, 7, 8, near);
    put(&mut d, 15, 8, far);
    put(&mut d, 23, 16, counter);
    put(&mut d, 39, 4, 1);
    frame(base + 0x600, 5, d)
}

/// One target's general values (metres, m/s, dBm²).
#[derive(Debug, Clone, Copy)]
pub struct General {
    pub id: u64,
    pub long: f64,
    pub lat: f64,
    pub vlong: f64,
    pub vlat: f64,
    pub dyn_prop: u64,
    pub rcs: f64,
}

impl General {
    pub fn at(id: u64, long: f64, lat: f64) -> Self {
        Self {
            id,
            long,
            lat,
            vlong: 0.0,
            vlat: 0.0,
            dyn_prop: 1,
            rcs: 5.0,
        }
    }
}

/// 0x701: DistLat 17|10 x0.2 -102.3.
pub fn cluster_general(base: u32, g: General) -> CanFrame {
    let mut d = general_common(g);
    put(&mut d, 17, 10, raw(g.lat, 0.2, -102.3));
    frame(base + 0x701, 8, d)
}

fn general_common(g: General) -> [u8; 8] {
    let mut d = [0; 8];
    put(&mut d, 7, 8, g.id);
    put(&mut d, 15, 13, raw(g.long, 0.2, -500.0));
    put(&mut d, 39, 10, raw(g.vlong, 0.25, -128.0));
    put(&mut d, 45, 9, raw(g.vlat, 0.25, -64.0));
    put(&mut d, 50, 3, g.dyn_prop);
    put(&mut d, 63, 8, raw(g.rcs, 0.5, -64.0));
    d
}

/// 0x702: id, DistLong_rms, DistLat_rms, Pdh0, InvalidState (codes).
pub fn cluster_quality(
    base: u32,
    id: u64,
    long_rms: u64,
    lat_rms: u64,
    pdh0: u64,
    invalid: u64,
) -> CanFrame {
    let mut d = [0; 8];
    put(&mut d, 7, 8, id);
    put(&mut d, 15, 5, long_rms);
    put(&mut d, 10, 5, lat_rms);
    put(&mut d, 26, 3, pdh0);
    put(&mut d, 39, 5, invalid);
    frame(base + 0x702, 5, d)
}

/// What a RadarState reports.
#[derive(Debug, Clone, Copy, Default)]
pub struct State {
    pub errors: [bool; 5],
    pub max_distance_m: u64,
    pub sensor_id: u64,
    pub output_type: u64,
    pub quality: bool,
    pub ext_info: bool,
    pub radar_power: u64,
}

impl State {
    pub fn clusters(quality: bool) -> Self {
        Self {
            max_distance_m: 196,
            output_type: 2,
            quality,
            ..Self::default()
        }
    }
}

/// 0x201.
pub fn radar_state(base: u32, s: State) -> CanFrame {
    let mut d = [0; 8];
    put(&mut d, 15, 10, s.max_distance_m / 2);
    for (k, set) in s.errors.iter().enumerate() {
        put(&mut d, 21 - k as u32, 1, u64::from(*set));
    }
    put(&mut d, 25, 3, s.radar_power);
    put(&mut d, 34, 3, s.sensor_id);
    put(&mut d, 43, 2, s.output_type);
    put(&mut d, 44, 1, u64::from(s.quality));
    put(&mut d, 45, 1, u64::from(s.ext_info));
    frame(base + 0x201, 8, d)
}

/// 0x60A: NofObjects, MeasCounter.
pub fn object_status(count: u64, counter: u64) -> CanFrame {
    let mut d = [0; 8];
    put(&mut d, 7, 8, count);
    put(&mut d, 15, 16, counter);
    frame(0x60A, 4, d)
}

/// 0x60B: DistLat 18|11 x0.2 -204.6.
pub fn object_general(g: General) -> CanFrame {
    let mut d = general_common(g);
    put(&mut d, 18, 11, raw(g.lat, 0.2, -204.6));
    frame(0x60B, 8, d)
}

/// 0x60C: id, MeasState 52|3, ProbOfExist 55|3.
pub fn object_quality(id: u64, meas_state: u64, prob: u64) -> CanFrame {
    let mut d = [0; 8];
    put(&mut d, 7, 8, id);
    put(&mut d, 52, 3, meas_state);
    put(&mut d, 55, 3, prob);
    frame(0x60C, 7, d)
}

/// 0x60D: id, Class 26|3, OrientationAngle 39|10 x0.4 -180, Length 55|8 x0.2,
/// Width 63|8 x0.2.
pub fn object_extended(
    id: u64,
    class: u64,
    orientation_deg: f64,
    length: f64,
    width: f64,
) -> CanFrame {
    let mut d = [0; 8];
    put(&mut d, 7, 8, id);
    put(&mut d, 15, 11, raw(0.0, 0.01, -10.0));
    put(&mut d, 20, 9, raw(0.0, 0.01, -2.5));
    put(&mut d, 26, 3, class);
    put(&mut d, 39, 10, raw(orientation_deg, 0.4, -180.0));
    put(&mut d, 55, 8, raw(length, 0.2, 0.0));
    put(&mut d, 63, 8, raw(width, 0.2, 0.0));
    frame(0x60D, 8, d)
}

/// A frame read at `ms` on the host (monotonic and stamp alike).
pub fn at(frame: CanFrame, ms: u64) -> TimedFrame {
    TimedFrame {
        frame,
        stamp_ns: 1_700_000_000_000_000_000 + ms * 1_000_000,
        clock: FrameClock::Kernel,
        received: host(ms),
    }
}

pub fn host(ms: u64) -> HostTime {
    HostTime::new(ms * 1_000_000, 1_700_000_000_000_000_000 + ms * 1_000_000)
}

/// A driver on the builtin DBC, connected (writable) at t = 0.
pub fn driver(config: Ars408Config) -> (Ars408Driver, Vec<CanDriverOutput>) {
    let mut d = Ars408Driver::new(config, builtin("ars408").unwrap()).unwrap();
    let mut out = Vec::new();
    d.connect(host(0), true, &mut out);
    (d, out)
}

/// Feeds frames, 1 ms apart from `start_ms`; returns everything output.
pub fn feed(d: &mut Ars408Driver, start_ms: u64, frames: &[CanFrame]) -> Vec<CanDriverOutput> {
    let mut out = Vec::new();
    for (k, f) in frames.iter().enumerate() {
        d.receive(&at(*f, start_ms + k as u64), &mut out);
    }
    out
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
