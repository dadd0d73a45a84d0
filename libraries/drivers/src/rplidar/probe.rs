//! The handshake's questions and what their answers taught: the order of the
//! queries (health, info, sample rate, scan modes, accessory board), which
//! of them a device may leave unanswered, and the `Identity` they add up to.
//! Everything here is rebuilt on every connect.

use std::collections::VecDeque;

use super::conf::{ConfQuery, LidarConf};
use super::config::MotorControl;
use super::motor::MotorDrive;
use super::plan::ScanPlan;
use super::protocol::{answer, cmd};
use super::replies::{DeviceInfo, Health, SampleRate};
use super::request;

/// A request that expects an answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Query {
    Health,
    Info,
    SampleRate,
    Conf(ConfQuery),
    AccBoardFlag,
    /// The scan start; its answer is a stream descriptor.
    StartScan,
}

impl Query {
    /// The answer type that answers it.
    pub fn answer_type(self) -> u8 {
        match self {
            Self::Health => answer::DEVHEALTH,
            Self::Info => answer::DEVINFO,
            Self::SampleRate => answer::SAMPLE_RATE,
            Self::Conf(_) => answer::LIDAR_CONF,
            Self::AccBoardFlag => answer::ACC_BOARD_FLAG,
            // Checked against the plan instead (`ScanPlan::expects`).
            Self::StartScan => 0,
        }
    }

    /// Devices may not answer these at all (older firmware, no accessory
    /// board): silence means "not supported", not a broken link.
    pub fn optional(self) -> bool {
        matches!(self, Self::SampleRate | Self::Conf(_) | Self::AccBoardFlag)
    }

    /// The request bytes (`plan` for [`Query::StartScan`]).
    pub fn request(self, plan: Option<&ScanPlan>) -> Vec<u8> {
        match self {
            Self::Health => request::encode(cmd::GET_HEALTH, &[]),
            Self::Info => request::encode(cmd::GET_INFO, &[]),
            Self::SampleRate => request::encode(cmd::GET_SAMPLERATE, &[]),
            Self::Conf(q) => q.request(),
            Self::AccBoardFlag => request::acc_board_flag(),
            Self::StartScan => plan.map(ScanPlan::request).unwrap_or_default(),
        }
    }

    /// For messages.
    pub fn name(self) -> String {
        match self {
            Self::Health => "GET_HEALTH".to_string(),
            Self::Info => "GET_INFO".to_string(),
            Self::SampleRate => "GET_SAMPLERATE".to_string(),
            Self::Conf(q) => format!("GET_LIDAR_CONF {:#04x}", q.key()),
            Self::AccBoardFlag => "GET_ACC_BOARD_FLAG".to_string(),
            Self::StartScan => "scan start".to_string(),
        }
    }
}

/// What one handshake has learned, and the questions still to ask.
#[derive(Debug, Clone, Default)]
pub struct Probe {
    pub health: Option<Health>,
    pub info: Option<DeviceInfo>,
    pub rate: Option<SampleRate>,
    pub conf: LidarConf,
    /// `GET_ACC_BOARD_FLAG` bit 0, if answered.
    pub board_pwm: Option<bool>,
    queue: VecDeque<Query>,
}

impl Probe {
    /// The next question, if any.
    pub fn next_query(&mut self) -> Option<Query> {
        self.queue.pop_front()
    }

    /// Plans the questions `info` makes worth asking.
    pub fn learn_info(&mut self, info: DeviceInfo, motor: MotorControl) {
        if info.supports_sample_rate() {
            self.queue.push_back(Query::SampleRate);
        }
        if info.supports_lidar_conf() {
            self.queue.push_back(Query::Conf(ConfQuery::ModeCount));
            self.queue.push_back(Query::Conf(ConfQuery::Typical));
        }
        if MotorDrive::needs_board_query(motor, &info) {
            self.queue.push_back(Query::AccBoardFlag);
        }
        self.info = Some(info);
    }

    /// After the mode count: ask about each mode next.
    pub fn plan_mode_queries(&mut self) {
        let ids: Vec<u16> = self.conf.modes.iter().map(|m| m.id).collect();
        for id in ids.into_iter().rev() {
            for q in ConfQuery::about_mode(id).into_iter().rev() {
                self.queue.push_front(Query::Conf(q));
            }
        }
    }

    /// The device does not answer `GET_LIDAR_CONF`: ask it nothing more.
    pub fn drop_conf_queries(&mut self) {
        self.queue.retain(|q| !matches!(q, Query::Conf(_)));
    }

    /// `key = value` pairs for `DriverOutput::Identity`.
    pub fn identity(&self, plan: &ScanPlan, motor: MotorDrive) -> Vec<(String, String)> {
        let mut pairs = Vec::new();
        let mut put = |k: &str, v: String| pairs.push((k.to_string(), v));
        if let Some(info) = &self.info {
            put("model", info.model_name());
            put("model_id", format!("{:#04x}", info.model));
            put("firmware", info.firmware_text());
            put("hardware", info.hardware.to_string());
            put("serial", info.serial_hex());
        }
        if let Some(rate) = self.rate {
            put("standard_sample_us", rate.standard_us.to_string());
            put("express_sample_us", rate.express_us.to_string());
        }
        for mode in &self.conf.modes {
            put(&format!("scan_mode_{}", mode.id), describe_mode(mode));
        }
        if let Some(id) = self.conf.typical {
            let name = self.conf.mode(id).and_then(|m| m.name.clone());
            put("typical_scan_mode", name.unwrap_or_else(|| id.to_string()));
        }
        put("scan_mode", plan.describe());
        put("motor_control", motor.describe());
        pairs
    }
}

fn describe_mode(mode: &super::conf::ScanModeInfo) -> String {
    let mut text = mode.name.clone().unwrap_or_else(|| "?".to_string());
    if let Some(t) = mode.answer_type {
        text.push_str(&format!(", answer {t:#04x}"));
    }
    if let Some(us) = mode.us_per_sample_q8 {
        text.push_str(&format!(", {:.1} us/sample", f64::from(us) / 256.0));
    }
    if let Some(m) = mode.max_distance_q8 {
        text.push_str(&format!(", {:.1} m", f64::from(m) / 256.0));
    }
    text
}
