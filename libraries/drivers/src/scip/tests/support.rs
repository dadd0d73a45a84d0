//! Test helpers: sensor-side reply builders (sums computed the spec's way)
//! and a rig that drives a [`ScipDriver`] on a scripted clock.

use crate::device::{DeviceDriver, DriverOutput, HostTime, RangeScan};
use crate::scip::{encode, line_sum, ScipConfig, ScipDriver, ECHO_MARK};

/// A line with its sum and LF.
pub fn summed(body: &str) -> String {
    format!("{body}{}\n", line_sum(body.as_bytes()) as char)
}

/// `KEY:VALUE;` and a sum over the line without the `;` (spec §8.12 style).
pub fn param(key: &str, value: &str) -> String {
    let body = format!("{key}:{value}");
    format!("{body};{}\n", line_sum(body.as_bytes()) as char)
}

/// A reply: echo, status with sum, `data` lines (already terminated), LF.
pub fn reply(echo: &str, status: &str, data: &[String]) -> Vec<u8> {
    let mut text = format!("{echo}\n{}", summed(status));
    text.extend(data.iter().map(String::as_str));
    text.push('\n');
    text.into_bytes()
}

/// The URG-04LX `PP` reply lines of the spec's example (spec §8.12, page 21);
/// the sums are the spec's except `MODL` and `ARES`, which the stored copy
/// garbles (recomputed here).
pub const URG04LX_PP: &str = "PP\n00P\n\
MODL:URG-04LX(Hokuyo Automatic Co., Ltd.);n\n\
DMIN:20;4\n\
DMAX:5600;_\n\
ARES:1024;\\\n\
AMIN:44;7\n\
AMAX:725;o\n\
AFRT:384;6\n\
SCAN:600;e\n\n";

pub fn vv_reply() -> Vec<u8> {
    let lines = [
        param("VEND", "Hokuyo Automatic Co., Ltd."),
        param("PROD", "SOKUIKI Sensor URG-04LX"),
        param("FIRM", "3.4.03(17/Dec./2007)"),
        param("PROT", "SCIP 2.0"),
        param("SERI", "H0722112"),
    ];
    reply("VV", "00", &lines)
}

pub fn ii_reply(stat: &str) -> Vec<u8> {
    let lines = [
        param("MODL", "URG-04LX"),
        param("LASR", "OFF"),
        param("SCSP", "Initial(600[rpm])"),
        param("MESM", "Measuring by Normal Mode"),
        param("SBPS", "19200[bps]"),
        param("TIME", "001234"),
        param("STAT", stat),
    ];
    reply("II", "00", &lines)
}

/// The data part of a scan: timestamp line, then `values` encoded in
/// `width` characters and cut into 64-character lines, each with its sum.
pub fn scan_lines(timestamp_ms: u32, values: &[u32], width: usize) -> Vec<String> {
    let text: Vec<u8> = values
        .iter()
        .flat_map(|&v| encode(v, width).unwrap())
        .collect();
    data_lines(timestamp_ms, &text)
}

/// The data part of a multi-echo scan: timestamp line, then each step's
/// echoes (`values_per_echo` 3-character values per echo: the range, or the
/// range and intensity), every echo after a step's first prefixed `&`, cut
/// into 64-character lines with sums.
pub fn multiecho_lines(
    timestamp_ms: u32,
    steps: &[Vec<u32>],
    values_per_echo: usize,
) -> Vec<String> {
    let mut text = Vec::new();
    for step in steps {
        for (echo, values) in step.chunks(values_per_echo).enumerate() {
            if echo > 0 {
                text.push(ECHO_MARK);
            }
            text.extend(values.iter().flat_map(|&v| encode(v, 3).unwrap()));
        }
    }
    data_lines(timestamp_ms, &text)
}

/// The timestamp line and `text` cut into 64-character lines, with sums.
fn data_lines(timestamp_ms: u32, text: &[u8]) -> Vec<String> {
    let stamp = String::from_utf8(encode(timestamp_ms, 4).unwrap()).unwrap();
    let mut lines = vec![summed(&stamp)];
    lines.extend(
        text.chunks(64)
            .map(|chunk| summed(std::str::from_utf8(chunk).unwrap())),
    );
    lines
}

/// A streamed scan reply (`99`).
pub fn streamed_scan(echo: &str, timestamp_ms: u32, values: &[u32], width: usize) -> Vec<u8> {
    reply(echo, "99", &scan_lines(timestamp_ms, values, width))
}

/// 682 URG-04LX values (steps 44..=725): a ramp with an error code at index
/// 0 (value 5 < DMIN), one value above DMAX at index 1, and 5432 mm ("1Dh")
/// at index 21, which straddles the first 64-character line boundary.
pub fn urg04lx_values() -> Vec<u32> {
    let mut values: Vec<u32> = (0..682).map(|i| 1000 + i).collect();
    values[0] = 5;
    values[1] = 6000;
    values[21] = 5432;
    values
}

pub const MD_FULL: &str = "MD0044072501000";

/// Monotonic and wall clock origins, and the sensor timer's value then.
pub const MONO0: u64 = 1_000_000_000;
pub const UNIX0: u64 = 1_700_000_000_000_000_000;

pub struct Rig {
    pub driver: ScipDriver,
    pub now: HostTime,
    /// The sensor timer (ms) at `MONO0`.
    pub dev0: u64,
}

impl Rig {
    pub fn new(config: ScipConfig) -> Self {
        Self {
            driver: ScipDriver::new(config),
            now: HostTime::new(MONO0, UNIX0),
            dev0: 5_000,
        }
    }

    pub fn connect(&mut self) -> Vec<DriverOutput> {
        let mut out = Vec::new();
        self.driver.connect(self.now, &mut out);
        out
    }

    /// Feeds bytes, then polls, as a node does.
    pub fn feed(&mut self, bytes: &[u8]) -> Vec<DriverOutput> {
        let mut out = Vec::new();
        self.driver.receive(bytes, self.now, &mut out);
        self.driver.poll(self.now, &mut out);
        out
    }

    pub fn advance_ms(&mut self, ms: u64) -> Vec<DriverOutput> {
        self.now = self.now.plus_ns(ms * 1_000_000);
        let mut out = Vec::new();
        self.driver.poll(self.now, &mut out);
        out
    }

    /// The sensor timer now, 24-bit.
    pub fn device_ms(&self) -> u32 {
        ((self.dev0 + (self.now.monotonic_ns - MONO0) / 1_000_000) & 0xFF_FFFF) as u32
    }

    /// The wall-clock time of unwrapped sensor time `dev_ms`.
    pub fn unix_at(&self, dev_ms: u64) -> u64 {
        let from_origin_ms = dev_ms as i64 - self.dev0 as i64;
        (UNIX0 as i64 + from_origin_ms * 1_000_000) as u64
    }

    /// `TM1` replies: round trip `k` takes 6 ms with the timer read 5 ms in,
    /// except round trip 2, which takes 2 ms with the timer read at its
    /// midpoint. Only the fastest one gives the true offset.
    pub fn answer_tm1(&mut self, rounds: u8) -> Vec<DriverOutput> {
        let mut out = Vec::new();
        for k in 0..rounds {
            let (read_at, rtt) = if k == 2 { (1, 2) } else { (5, 6) };
            self.advance_ms(read_at);
            let stamp = String::from_utf8(encode(self.device_ms(), 4).unwrap()).unwrap();
            self.advance_ms(rtt - read_at);
            out.extend(self.feed(&reply("TM1", "00", &[summed(&stamp)])));
        }
        out
    }

    /// From `connect` to the measurement command written, USB, no checks.
    pub fn bring_up(&mut self) -> Vec<DriverOutput> {
        let mut out = self.connect();
        out.extend(self.feed(&reply("QT", "00", &[])));
        out.extend(self.feed(&vv_reply()));
        out.extend(self.feed(URG04LX_PP.as_bytes()));
        out.extend(self.feed(&ii_reply("Sensor works well.")));
        let rounds = self.driver.config().tm_round_trips;
        if rounds > 0 {
            out.extend(self.feed(&reply("TM0", "00", &[])));
            out.extend(self.answer_tm1(rounds));
            out.extend(self.feed(&reply("TM2", "00", &[])));
        }
        out
    }

    /// A default (MD, USB) driver streaming the URG-04LX's full range.
    pub fn streaming() -> Self {
        let mut rig = Self::new(ScipConfig::default());
        rig.bring_up();
        rig.feed(&reply(MD_FULL, "00", &[]));
        rig
    }

    /// A URG-04LX MD scan reply whose timestamp is `age_ms` before now.
    pub fn md_scan(&self, age_ms: u32) -> Vec<u8> {
        let stamp = self.device_ms().wrapping_sub(age_ms) & 0xFF_FFFF;
        streamed_scan(MD_FULL, stamp, &urg04lx_values(), 3)
    }
}

pub fn writes(out: &[DriverOutput]) -> Vec<String> {
    out.iter()
        .filter_map(|o| match o {
            DriverOutput::Write(bytes) => Some(String::from_utf8_lossy(bytes).into_owned()),
            _ => None,
        })
        .collect()
}

/// A scan as comparable bits (NaN ranges compare equal to themselves).
pub type ScanBits = (u32, u64, HostTime, Vec<(u32, u32, Option<u32>, u32)>);

pub fn scan_bits(scan: &RangeScan) -> ScanBits {
    let rays = scan
        .rays
        .iter()
        .map(|r| {
            (
                r.angle.to_bits(),
                r.range.to_bits(),
                r.intensity.map(f32::to_bits),
                r.offset_ns,
            )
        })
        .collect();
    (scan.sequence, scan.stamp_ns, scan.received, rays)
}

pub fn scans(out: &[DriverOutput]) -> Vec<RangeScan> {
    out.iter()
        .filter_map(|o| match o {
            DriverOutput::Scan(scan) => Some(scan.clone()),
            _ => None,
        })
        .collect()
}

pub fn reconnect_reason(out: &[DriverOutput]) -> Option<String> {
    out.iter().find_map(|o| match o {
        DriverOutput::Reconnect(reason) => Some(reason.clone()),
        _ => None,
    })
}

pub fn identity(out: &[DriverOutput]) -> Option<Vec<(String, String)>> {
    out.iter().find_map(|o| match o {
        DriverOutput::Identity(pairs) => Some(pairs.clone()),
        _ => None,
    })
}

pub fn identity_value(pairs: &[(String, String)], key: &str) -> Option<String> {
    pairs.iter().find(|(k, _)| k == key).map(|(_, v)| v.clone())
}
