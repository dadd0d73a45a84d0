//! Test-side encoders of what an RPLIDAR sends (descriptors, answers, nodes,
//! capsules) and a scripted fake device that answers the driver's requests.

use crate::device::{DeviceDriver, DeviceStats, DriverOutput, HostTime, RangeScan, Ray};
use crate::rplidar::capsule::checksum_ok;
use crate::rplidar::protocol::{answer, CAPSULE_LEN};
use crate::rplidar::revolution::{Revolution, RevolutionAssembler};
use crate::rplidar::stream::{SampleFormat, StreamDecoder};
use crate::rplidar::timing::SampleClock;
use crate::rplidar::RplidarDriver;

pub fn descriptor(len: u32, multiple: bool, answer_type: u8) -> Vec<u8> {
    let word = len | if multiple { 1 << 30 } else { 0 };
    let mut d = vec![0xA5, 0x5A];
    d.extend_from_slice(&word.to_le_bytes());
    d.push(answer_type);
    d
}

pub fn reply(answer_type: u8, payload: &[u8]) -> Vec<u8> {
    let mut r = descriptor(payload.len() as u32, false, answer_type);
    r.extend_from_slice(payload);
    r
}

pub fn info_payload(model: u8, major: u8, minor: u8, hardware: u8) -> Vec<u8> {
    let mut p = vec![model, minor, major, hardware];
    p.extend(0u8..16);
    p
}

pub fn conf_reply(key: u32, value: &[u8]) -> Vec<u8> {
    let mut p = key.to_le_bytes().to_vec();
    p.extend_from_slice(value);
    reply(answer::LIDAR_CONF, &p)
}

pub fn node(quality: u8, start: bool, angle_q6: u16, distance_q2: u16) -> [u8; 5] {
    let b0 = quality << 2 | if start { 0b01 } else { 0b10 };
    let a = (angle_q6 << 1) | 1;
    let [a0, a1] = a.to_le_bytes();
    let [d0, d1] = distance_q2.to_le_bytes();
    [b0, a0, a1, d0, d1]
}

/// Sets b0/b1 to the sync nibbles and the checksum of b2..84.
pub fn seal(capsule: &mut [u8; CAPSULE_LEN]) {
    let sum = capsule[2..].iter().fold(0u8, |a, b| a ^ b);
    capsule[0] = 0xA0 | (sum & 0x0F);
    capsule[1] = 0x50 | (sum >> 4);
    assert!(checksum_ok(capsule));
}

fn with_start(start_q6: u16, restart: bool) -> [u8; CAPSULE_LEN] {
    let mut c = [0u8; CAPSULE_LEN];
    let raw = start_q6 | if restart { 0x8000 } else { 0 };
    c[2..4].copy_from_slice(&raw.to_le_bytes());
    c
}

/// An express capsule: 32 samples of (distance q2, dθ q3 0..63).
pub fn express_capsule(
    start_q6: u16,
    restart: bool,
    samples: &[(u16, u8); 32],
) -> [u8; CAPSULE_LEN] {
    let mut c = with_start(start_q6, restart);
    for (i, pair) in samples.chunks(2).enumerate() {
        let ((d1, o1), (d2, o2)) = (pair[0], pair[1]);
        let a = (d1 & 0xFFFC) | u16::from(o1 >> 4);
        let b = (d2 & 0xFFFC) | u16::from(o2 >> 4);
        let at = 4 + i * 5;
        c[at..at + 2].copy_from_slice(&a.to_le_bytes());
        c[at + 2..at + 4].copy_from_slice(&b.to_le_bytes());
        c[at + 4] = (o1 & 0x0F) | ((o2 & 0x0F) << 4);
    }
    seal(&mut c);
    c
}

/// A dense capsule: 40 distances in mm.
pub fn dense_capsule(start_q6: u16, restart: bool, distances: &[u16; 40]) -> [u8; CAPSULE_LEN] {
    let mut c = with_start(start_q6, restart);
    for (i, d) in distances.iter().enumerate() {
        c[4 + 2 * i..6 + 2 * i].copy_from_slice(&d.to_le_bytes());
    }
    seal(&mut c);
    c
}

/// A tiny deterministic generator for test data (no wire meaning).
pub struct Lcg(pub u64);
impl Lcg {
    pub fn next(&mut self) -> u32 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 33) as u32
    }
}

/// `revolutions` standard revolutions of `per_rev` nodes (plus a partial one
/// before and half of the next after, which confirms the last boundary).
pub fn standard_stream(revolutions: usize, per_rev: usize, seed: u64) -> Vec<u8> {
    let mut rng = Lcg(seed);
    let mut bytes = Vec::new();
    let step = (360 * 64 / per_rev) as u16;
    let total = per_rev / 3 + revolutions * per_rev + per_rev / 2;
    for i in 0..total {
        let k = (i + per_rev - per_rev / 3) % per_rev;
        let distance = if rng.next().is_multiple_of(8) {
            0
        } else {
            (rng.next() % 40000) as u16 + 4
        };
        bytes.extend(node(
            (rng.next() % 64) as u8,
            k == 0,
            k as u16 * step,
            distance,
        ));
    }
    bytes
}

/// An express stream: a restart capsule, then capsules 15° apart for about
/// `revolutions` turns and a bit.
pub fn express_stream(revolutions: usize, seed: u64) -> Vec<u8> {
    let mut rng = Lcg(seed);
    let mut bytes = Vec::new();
    for i in 0..(revolutions * 24 + 30) {
        let start = ((100 + i * 15) % 360 * 64) as u16;
        let samples: [(u16, u8); 32] = std::array::from_fn(|_| {
            let d = if rng.next().is_multiple_of(8) {
                0
            } else {
                (rng.next() % 60000) as u16 & 0xFFFC
            };
            (d, (rng.next() % 64) as u8)
        });
        bytes.extend(express_capsule(start, i == 0, &samples));
    }
    bytes
}

/// A dense stream, capsules 20° apart (18 a turn).
pub fn dense_stream(revolutions: usize, seed: u64) -> Vec<u8> {
    let mut rng = Lcg(seed);
    let mut bytes = Vec::new();
    for i in 0..(revolutions * 18 + 20) {
        let start = ((37 + i * 20) % 360 * 64) as u16;
        let d: [u16; 40] = std::array::from_fn(|_| (rng.next() % 12000) as u16);
        bytes.extend(dense_capsule(start, i == 0, &d));
    }
    bytes
}

pub fn clock() -> SampleClock {
    SampleClock::new(125 << 8, 256_000)
}

/// Decodes a stream with `chunks` boundaries, all at one time.
pub fn decode(format: SampleFormat, chunks: &[&[u8]]) -> (Vec<Revolution>, DeviceStats) {
    let mut decoder = StreamDecoder::new(format, clock());
    let mut assembler = RevolutionAssembler::new(8192, format.boundary_confirmation());
    let mut stats = DeviceStats::default();
    let mut revs = Vec::new();
    let mut events = Vec::new();
    for chunk in chunks {
        decoder.feed(chunk, t(0), &mut stats, &mut events);
        for e in events.drain(..) {
            revs.extend(assembler.push(e, &mut stats));
        }
    }
    (revs, stats)
}

pub fn t(ms: u64) -> HostTime {
    HostTime::new(ms * 1_000_000, 1_700_000_000_000_000_000 + ms * 1_000_000)
}

/// Rays equal bit for bit (NaN equals NaN).
pub fn same_ray(a: &Ray, b: &Ray) -> bool {
    a.angle.to_bits() == b.angle.to_bits()
        && a.range.to_bits() == b.range.to_bits()
        && a.intensity.map(f32::to_bits) == b.intensity.map(f32::to_bits)
        && a.offset_ns == b.offset_ns
}

pub fn same_rays(a: &[Ray], b: &[Ray]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| same_ray(x, y))
}

/// A driver plus a clock, collecting outputs.
pub struct Harness {
    pub driver: RplidarDriver,
    pub now_ms: u64,
}

impl Harness {
    pub fn new(driver: RplidarDriver) -> Self {
        Self { driver, now_ms: 0 }
    }
    pub fn connect(&mut self) -> Vec<DriverOutput> {
        let mut out = Vec::new();
        self.driver.connect(t(self.now_ms), &mut out);
        out
    }
    pub fn wait(&mut self, ms: u64) -> Vec<DriverOutput> {
        self.now_ms += ms;
        let mut out = Vec::new();
        self.driver.poll(t(self.now_ms), &mut out);
        out
    }
    pub fn feed(&mut self, bytes: &[u8]) -> Vec<DriverOutput> {
        let mut out = Vec::new();
        self.driver.receive(bytes, t(self.now_ms), &mut out);
        self.driver.poll(t(self.now_ms), &mut out);
        out
    }
}

pub fn writes(out: &[DriverOutput]) -> Vec<Vec<u8>> {
    out.iter()
        .filter_map(|o| match o {
            DriverOutput::Write(w) => Some(w.clone()),
            _ => None,
        })
        .collect()
}

pub fn scans(out: &[DriverOutput]) -> Vec<RangeScan> {
    out.iter()
        .filter_map(|o| match o {
            DriverOutput::Scan(s) => Some(s.clone()),
            _ => None,
        })
        .collect()
}

/// A fake device: answers each request it understands as configured.
#[derive(Debug, Clone)]
pub struct FakeLidar {
    pub info: Vec<u8>,
    pub health: [u8; 3],
    pub sample_rate: Option<[u8; 4]>,
    /// (name, answer type, µs q8) per mode; empty: no GET_LIDAR_CONF answers.
    pub modes: Vec<(&'static str, u8, u32)>,
    pub typical: u16,
    pub board_flag: Option<u32>,
    /// What follows a scan start's descriptor.
    pub stream: Vec<u8>,
}

impl FakeLidar {
    /// The bytes the device sends in answer to `request`.
    pub fn answer(&self, request: &[u8]) -> Vec<u8> {
        match request {
            [0xA5, 0x52] => reply(answer::DEVHEALTH, &self.health),
            [0xA5, 0x50] => reply(answer::DEVINFO, &self.info),
            [0xA5, 0x59] => self
                .sample_rate
                .map(|r| reply(answer::SAMPLE_RATE, &r))
                .unwrap_or_default(),
            [0xA5, 0x84, _, k0, k1, k2, k3, rest @ ..] if !self.modes.is_empty() => {
                let key = u32::from_le_bytes([*k0, *k1, *k2, *k3]);
                let mode = match rest {
                    [m0, m1, _] => Some(usize::from(u16::from_le_bytes([*m0, *m1]))),
                    _ => None,
                };
                self.conf(key, mode)
            }
            [0xA5, 0xFF, ..] => self
                .board_flag
                .map(|f| reply(answer::ACC_BOARD_FLAG, &f.to_le_bytes()))
                .unwrap_or_default(),
            [0xA5, 0x20] => {
                let mut s = descriptor(5, true, answer::MEASUREMENT);
                s.extend_from_slice(&self.stream);
                s
            }
            [0xA5, 0x82, 5, mode, ..] => {
                let ty = if *mode == 0 {
                    answer::CAPSULED
                } else {
                    self.modes[usize::from(*mode)].1
                };
                let mut s = descriptor(84, true, ty);
                s.extend_from_slice(&self.stream);
                s
            }
            _ => Vec::new(),
        }
    }

    fn conf(&self, key: u32, mode: Option<usize>) -> Vec<u8> {
        let m = mode.and_then(|m| self.modes.get(m));
        match (key, m) {
            (0x70, _) => conf_reply(key, &(self.modes.len() as u16).to_le_bytes()),
            (0x7C, _) => conf_reply(key, &self.typical.to_le_bytes()),
            (0x7F, Some(m)) => conf_reply(key, format!("{}\0", m.0).as_bytes()),
            (0x75, Some(m)) => conf_reply(key, &[m.1]),
            (0x71, Some(m)) => conf_reply(key, &m.2.to_le_bytes()),
            (0x74, Some(_)) => conf_reply(key, &(12u32 << 8).to_le_bytes()),
            _ => Vec::new(),
        }
    }

    /// Runs a connect against this device: every write answered at once;
    /// unanswered requests wait out the timeout. Returns all outputs.
    pub fn run(&self, harness: &mut Harness, max_steps: usize) -> Vec<DriverOutput> {
        let mut all = harness.connect();
        all.extend(harness.wait(100));
        for answered in 0..max_steps {
            let pending = writes(&all);
            let Some(request) = pending.get(answered) else {
                break;
            };
            let bytes = self.answer(request);
            if bytes.is_empty() {
                if matches!(request.get(1), Some(0x25 | 0x40 | 0xF0 | 0xA8)) {
                    continue;
                }
                all.extend(harness.wait(1000));
            } else {
                all.extend(harness.feed(&bytes));
            }
        }
        all
    }
}
