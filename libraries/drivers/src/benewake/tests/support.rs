//! Test helpers: frames and replies as a device sends them, and a bench that
//! runs the driver against a scripted byte stream on a fake clock.

use crate::benewake::{
    command_id, encode_frame, BenewakeConfig, BenewakeDriver, Command, DataFrame,
};
use crate::device::{DeviceDriver, DeviceState, DriverOutput, HostTime, RangeScan};

/// Unix time of the bench's clock at monotonic 0.
pub const EPOCH_NS: u64 = 1_700_000_000_000_000_000;

/// A data frame's bytes.
pub fn frame(distance: u16, strength: u16, aux: u16) -> [u8; 9] {
    DataFrame {
        distance,
        strength,
        aux,
    }
    .encode()
}

/// The device's reply to `command` (echo, version or status).
pub fn reply_to(command: Command) -> Vec<u8> {
    match command {
        Command::Version => encode_frame(command_id::VERSION, &[112, 50, 9]),
        Command::SoftReset | Command::FactoryReset | Command::Save => {
            encode_frame(command.id(), &[0])
        }
        other => other.encode(),
    }
}

/// The driver on a fake clock.
pub struct Bench {
    pub driver: BenewakeDriver,
    pub now: HostTime,
}

impl Bench {
    pub fn new(config: BenewakeConfig) -> Self {
        Self {
            driver: BenewakeDriver::new(config),
            now: HostTime::new(0, EPOCH_NS),
        }
    }

    pub fn connect(&mut self) -> Vec<DriverOutput> {
        let mut out = Vec::new();
        self.driver.connect(self.now, &mut out);
        out
    }

    /// Feeds `bytes` at the current time, then polls (as the node does).
    pub fn feed(&mut self, bytes: &[u8]) -> Vec<DriverOutput> {
        let mut out = Vec::new();
        self.driver.receive(bytes, self.now, &mut out);
        self.driver.poll(self.now, &mut out);
        out
    }

    /// Moves the clock `ms` on and polls.
    pub fn wait_ms(&mut self, ms: u64) -> Vec<DriverOutput> {
        self.now = self.now.plus_ns(ms * 1_000_000);
        let mut out = Vec::new();
        self.driver.poll(self.now, &mut out);
        out
    }

    /// Connects and answers every command with its reply, a data frame before
    /// each, until the driver streams; returns everything the driver said.
    pub fn handshake(&mut self) -> Vec<DriverOutput> {
        let mut all = self.connect();
        let mut pending = writes(&all);
        while self.driver.state() != &DeviceState::Streaming {
            let Some(command) = pending.pop() else { break };
            let mut bytes = frame(100, 500, 2248).to_vec();
            bytes.extend(reply_for_bytes(&command));
            let out = self.feed(&bytes);
            pending = writes(&out);
            all.extend(out);
        }
        all
    }
}

/// The reply a device gives to the command frame `bytes`.
pub fn reply_for_bytes(bytes: &[u8]) -> Vec<u8> {
    let command = match bytes.get(2).copied() {
        Some(command_id::VERSION) => Command::Version,
        Some(command_id::SAVE) => Command::Save,
        Some(command_id::TRIGGER) => return Vec::new(),
        _ => return bytes.to_vec(), // the other commands are echoed
    };
    reply_to(command)
}

pub fn writes(out: &[DriverOutput]) -> Vec<Vec<u8>> {
    out.iter()
        .filter_map(|o| match o {
            DriverOutput::Write(bytes) => Some(bytes.clone()),
            _ => None,
        })
        .collect()
}

pub fn scans(out: &[DriverOutput]) -> Vec<RangeScan> {
    out.iter()
        .filter_map(|o| match o {
            DriverOutput::Scan(scan) => Some(scan.clone()),
            _ => None,
        })
        .collect()
}

pub fn identity(out: &[DriverOutput]) -> Option<Vec<(String, String)>> {
    out.iter().find_map(|o| match o {
        DriverOutput::Identity(pairs) => Some(pairs.clone()),
        _ => None,
    })
}

pub fn identity_value(out: &[DriverOutput], key: &str) -> Option<String> {
    identity(out)?
        .into_iter()
        .find(|(k, _)| k == key)
        .map(|(_, v)| v)
}

pub fn reconnect_reason(out: &[DriverOutput]) -> Option<String> {
    out.iter().find_map(|o| match o {
        DriverOutput::Reconnect(reason) => Some(reason.clone()),
        _ => None,
    })
}
