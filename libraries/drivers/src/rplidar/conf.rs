//! `GET_LIDAR_CONF` (firmware 1.24+): the queries the handshake makes about
//! the device's scan modes, and the decoding of their answers.
//!
//! Request payload `type u32 LE` (+ `mode id u16 LE` for per-mode keys); the
//! answer (type 0x20) is `type u32 LE` echoing the key, then the value
//! (`getLidarConf`, `getScanModeCount`, `getLidarSampleDuration`,
//! `getMaxDistance`, `getScanModeAnsType`, `getScanModeName`,
//! `getTypicalScanMode` in `sl_lidar_driver.cpp`).

use super::protocol::conf;
use super::replies::ShortReply;
use super::request;

/// At most this many scan modes are queried (A series reports 5, S series 3).
pub const MAX_SCAN_MODES: u16 = 16;
/// Longest mode name kept, in bytes (the SDK's buffer is 64).
const MAX_NAME_LEN: usize = 64;

/// One `GET_LIDAR_CONF` question.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ConfQuery {
    /// `SCAN_MODE_COUNT` → `u16`.
    ModeCount,
    /// `SCAN_MODE_TYPICAL` → `u16` mode id.
    Typical,
    /// `SCAN_MODE_US_PER_SAMPLE` → `u32`, µs in q8.
    UsPerSample(u16),
    /// `SCAN_MODE_MAX_DISTANCE` → `u32`, metres in q8.
    MaxDistance(u16),
    /// `SCAN_MODE_ANS_TYPE` → `u8` answer type of the mode's stream.
    AnswerType(u16),
    /// `SCAN_MODE_NAME` → a string, NUL-terminated or not.
    Name(u16),
}

impl ConfQuery {
    /// The configuration key.
    pub fn key(self) -> u32 {
        match self {
            Self::ModeCount => conf::SCAN_MODE_COUNT,
            Self::Typical => conf::SCAN_MODE_TYPICAL,
            Self::UsPerSample(_) => conf::SCAN_MODE_US_PER_SAMPLE,
            Self::MaxDistance(_) => conf::SCAN_MODE_MAX_DISTANCE,
            Self::AnswerType(_) => conf::SCAN_MODE_ANS_TYPE,
            Self::Name(_) => conf::SCAN_MODE_NAME,
        }
    }

    fn mode(self) -> Option<u16> {
        match self {
            Self::ModeCount | Self::Typical => None,
            Self::UsPerSample(m) | Self::MaxDistance(m) | Self::AnswerType(m) | Self::Name(m) => {
                Some(m)
            }
        }
    }

    /// The request bytes.
    pub fn request(self) -> Vec<u8> {
        request::lidar_conf(self.key(), self.mode())
    }

    /// The four per-mode questions about `mode`.
    pub fn about_mode(mode: u16) -> [Self; 4] {
        [
            Self::Name(mode),
            Self::AnswerType(mode),
            Self::UsPerSample(mode),
            Self::MaxDistance(mode),
        ]
    }
}

/// Splits a `GET_LIDAR_CONF` answer into the key it answers and its value.
pub fn split_answer(payload: &[u8]) -> Result<(u32, &[u8]), ShortReply> {
    match payload.split_first_chunk::<4>() {
        Some((key, value)) => Ok((u32::from_le_bytes(*key), value)),
        None => Err(ShortReply {
            what: "GET_LIDAR_CONF",
            needed: 4,
            got: payload.len(),
        }),
    }
}

/// What the device said about one scan mode (each field `None` when the
/// device did not answer that question).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct ScanModeInfo {
    pub id: u16,
    pub name: Option<String>,
    pub answer_type: Option<u8>,
    /// µs per sample, q8.
    pub us_per_sample_q8: Option<u32>,
    /// Metres, q8.
    pub max_distance_q8: Option<u32>,
}

/// Everything `GET_LIDAR_CONF` told this handshake.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct LidarConf {
    pub mode_count: Option<u16>,
    pub typical: Option<u16>,
    pub modes: Vec<ScanModeInfo>,
}

fn value<const N: usize>(bytes: &[u8]) -> Result<[u8; N], ShortReply> {
    bytes.first_chunk::<N>().copied().ok_or(ShortReply {
        what: "GET_LIDAR_CONF value",
        needed: N,
        got: bytes.len(),
    })
}

fn mode_name(bytes: &[u8]) -> String {
    let end = bytes.iter().position(|&b| b == 0).unwrap_or(bytes.len());
    let text = bytes.get(..end.min(MAX_NAME_LEN)).unwrap_or_default();
    String::from_utf8_lossy(text).trim().to_string()
}

impl LidarConf {
    /// Records the answer `bytes` to `query`. The mode count is capped at
    /// [`MAX_SCAN_MODES`]; answers about a mode id beyond it are ignored.
    pub fn record(&mut self, query: ConfQuery, bytes: &[u8]) -> Result<(), ShortReply> {
        match query {
            ConfQuery::ModeCount => {
                let count = u16::from_le_bytes(value(bytes)?);
                self.mode_count = Some(count);
                self.modes = (0..count.min(MAX_SCAN_MODES))
                    .map(|id| ScanModeInfo {
                        id,
                        ..ScanModeInfo::default()
                    })
                    .collect();
            }
            ConfQuery::Typical => self.typical = Some(u16::from_le_bytes(value(bytes)?)),
            ConfQuery::UsPerSample(m) => {
                let v = u32::from_le_bytes(value(bytes)?);
                self.update(m, |info| info.us_per_sample_q8 = Some(v));
            }
            ConfQuery::MaxDistance(m) => {
                let v = u32::from_le_bytes(value(bytes)?);
                self.update(m, |info| info.max_distance_q8 = Some(v));
            }
            ConfQuery::AnswerType(m) => {
                let [v] = value(bytes)?;
                self.update(m, |info| info.answer_type = Some(v));
            }
            ConfQuery::Name(m) => {
                let name = mode_name(bytes);
                self.update(m, |info| info.name = Some(name));
            }
        }
        Ok(())
    }

    fn update(&mut self, id: u16, set: impl FnOnce(&mut ScanModeInfo)) {
        if let Some(info) = self.modes.iter_mut().find(|m| m.id == id) {
            set(info);
        }
    }

    /// The mode with this id, if the device listed it.
    pub fn mode(&self, id: u16) -> Option<&ScanModeInfo> {
        self.modes.iter().find(|m| m.id == id)
    }

    /// The first listed mode whose stream has `answer_type`.
    pub fn mode_with_answer(&self, answer_type: u8) -> Option<&ScanModeInfo> {
        self.modes
            .iter()
            .find(|m| m.answer_type == Some(answer_type))
    }
}
