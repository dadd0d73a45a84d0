//! The Benewake CAN driver: every configured rangefinder's frames in, one
//! cloud per cycle out ([`CanDeviceDriver`]).

use super::config::BenewakeCanConfig;
use super::cycle::{ClosedCycle, CycleBuilder, Report};
use super::error::BenewakeCanError;
use super::reading::{ModelDecoder, DEVICE_TIME_MODULUS_MS};
use crate::can_device::{CanDeviceDriver, CanDriverOutput, SensorCloud, TimedFrame};
use crate::device::{DeviceState, DeviceStats, HostTime};
use crate::Scan;
use glam::DVec3;
use shroud_msg::PointChannel;

/// Several Benewake rangefinders on one bus.
#[derive(Debug, Clone)]
pub struct BenewakeCanDriver {
    config: BenewakeCanConfig,
    decoders: Vec<ModelDecoder>,
    cycle: CycleBuilder,
    /// Per sensor: the last device timestamp, to spot repeated readings.
    last_timestamp: Vec<Option<u32>>,
    /// Per sensor: cycles that closed without its reading.
    missing: Vec<(String, u64)>,
    with_device_time: bool,
    sequence: u32,
    state: DeviceState,
    stats: DeviceStats,
    connected_at: HostTime,
    last_frame: Option<HostTime>,
    silent: bool,
}

impl BenewakeCanDriver {
    /// A driver for `config` (validated), each sensor read through its
    /// model's builtin DBC.
    pub fn new(config: BenewakeCanConfig) -> Result<Self, BenewakeCanError> {
        config.validate()?;
        let decoders = config
            .sensors
            .iter()
            .map(|s| ModelDecoder::new(s.model))
            .collect::<Result<Vec<_>, _>>()?;
        let n = config.sensors.len();
        Ok(Self {
            decoders,
            cycle: CycleBuilder::new(n),
            last_timestamp: vec![None; n],
            missing: config.sensors.iter().map(|s| (s.name.clone(), 0)).collect(),
            with_device_time: config.sensors.iter().any(|s| s.model.has_timestamp()),
            sequence: 0,
            state: DeviceState::Disconnected,
            stats: DeviceStats::default(),
            connected_at: HostTime::default(),
            last_frame: None,
            silent: false,
            config,
        })
    }

    pub fn config(&self) -> &BenewakeCanConfig {
        &self.config
    }

    /// Per sensor (by name, in configuration order): cycles that closed
    /// without its reading (their sum is the `missing_reading` error count).
    pub fn missing_by_sensor(&self) -> &[(String, u64)] {
        &self.missing
    }

    fn set_state(&mut self, state: DeviceState, out: &mut Vec<CanDriverOutput>) {
        if self.state != state {
            self.state = state.clone();
            out.push(CanDriverOutput::State(state));
        }
    }

    /// Counts the missing and publishes the cloud: one point per valid
    /// reading in sensor order, intensity = strength, channels `strength`,
    /// `sensor_index` (the sensor's position in the configuration) and, when
    /// any sensor's model has a timestamp, `device_time_ms` (the device's ms
    /// counter modulo [`DEVICE_TIME_MODULUS_MS`], `NaN` for models without).
    /// A cycle of invalid readings only is an empty cloud, still published.
    fn publish(&mut self, cycle: ClosedCycle, out: &mut Vec<CanDriverOutput>) {
        for k in cycle.missing() {
            self.stats.count("missing_reading");
            if let Some((_, n)) = self.missing.get_mut(k) {
                *n += 1;
            }
        }
        let mut points = Vec::new();
        let mut strength = Vec::new();
        let mut index = Vec::new();
        let mut device_time = Vec::new();
        for (k, report) in cycle.reports.iter().enumerate() {
            let Some(report) = report else { continue };
            let Some(point) = report.point else { continue };
            points.push(point);
            strength.push(report.strength as f32);
            index.push(k as f32);
            device_time.push(
                report
                    .device_time_ms
                    .map_or(f32::NAN, |t| (t % DEVICE_TIME_MODULUS_MS) as f32),
            );
        }
        let mut scan = Scan::new(self.sequence, cycle.stamp_ns, points);
        self.sequence = self.sequence.wrapping_add(1);
        scan.intensity = Some(strength.clone());
        scan.channels = vec![
            PointChannel::new("strength", strength),
            PointChannel::new("sensor_index", index),
        ];
        if self.with_device_time {
            scan.channels
                .push(PointChannel::new("device_time_ms", device_time));
        }
        self.stats.scans += 1;
        out.push(CanDriverOutput::Cloud(SensorCloud {
            scan,
            received: cycle.received,
        }));
    }
}

impl CanDeviceDriver for BenewakeCanDriver {
    fn kind(&self) -> &'static str {
        "benewake_can"
    }

    fn connect(&mut self, now: HostTime, _writable: bool, out: &mut Vec<CanDriverOutput>) {
        if self.cycle.reset() {
            self.stats.note("cycle_cut");
        }
        self.last_timestamp.iter_mut().for_each(|t| *t = None);
        self.connected_at = now;
        self.last_frame = None;
        self.silent = false;
        self.set_state(DeviceState::Connecting, out);
        // What is on the bus, as configured (the devices do not say).
        let sensors = &self.config.sensors;
        let mut models: Vec<&str> = sensors.iter().map(|s| s.model.name()).collect();
        models.dedup();
        let ids: Vec<String> = sensors
            .iter()
            .map(|s| format!("{}@{:#x}", s.name, s.id))
            .collect();
        out.push(CanDriverOutput::Identity(vec![
            ("model".to_owned(), models.join(",")),
            ("rangefinders".to_owned(), ids.join(",")),
        ]));
    }

    fn receive(&mut self, frame: &TimedFrame, out: &mut Vec<CanDriverOutput>) {
        let f = &frame.frame;
        self.stats.bytes += f.payload().len() as u64;
        let sensor = self
            .config
            .sensors
            .iter()
            .position(|s| s.id == f.id && s.extended == f.extended);
        let Some(k) = sensor else {
            self.stats.note("other_id");
            return;
        };
        let (Some(decoder), Some(sensor)) = (self.decoders.get(k), self.config.sensors.get(k))
        else {
            return;
        };
        let Some(reading) = decoder.decode(f) else {
            self.stats.count("bad_frame");
            return;
        };
        let mount = sensor.mount;
        self.last_frame = Some(frame.received);
        self.silent = false;
        if self.state != DeviceState::Streaming {
            if self.state == DeviceState::Connecting {
                self.stats.handshakes += 1;
            }
            self.set_state(DeviceState::Streaming, out);
        }
        if let (Some(t), Some(last)) = (reading.timestamp_ms, self.last_timestamp.get_mut(k)) {
            // The device stamps each measurement: the same stamp again is
            // the same measurement sent twice, not a new one.
            if *last == Some(t) {
                self.stats.note("repeated_reading");
                return;
            }
            *last = Some(t);
        }
        if let Some(kind) = reading.validity.counter() {
            self.stats.count_invalid_reading(kind);
        }
        let point = reading.range_m.is_finite().then(|| {
            let p = mount.apply(DVec3::new(f64::from(reading.range_m), 0.0, 0.0));
            [p.x as f32, p.y as f32, p.z as f32]
        });
        let report = Report {
            point,
            strength: reading.strength,
            device_time_ms: reading.timestamp_ms,
        };
        let mut done = Vec::new();
        // A cycle whose time ran out before this frame closes without it,
        // even when no poll came between (the node polls a quiet bus only).
        if let Some(expired) = self
            .cycle
            .poll(frame.received, self.config.cycle_timeout_ns)
        {
            done.push(expired);
        }
        self.cycle
            .add(k, report, frame.stamp_ns, frame.received, &mut done);
        for cycle in done {
            self.publish(cycle, out);
        }
    }

    fn poll(&mut self, now: HostTime, out: &mut Vec<CanDriverOutput>) {
        if self.state == DeviceState::Disconnected {
            return;
        }
        if let Some(cycle) = self.cycle.poll(now, self.config.cycle_timeout_ns) {
            self.publish(cycle, out);
        }
        let quiet = now.since(self.last_frame.unwrap_or(self.connected_at));
        if !self.silent && quiet >= self.config.silence_timeout_ns {
            self.silent = true;
            self.stats.count("silent");
            let reason = format!(
                "no frames from the rangefinders for {:.1} s",
                quiet as f64 * 1e-9
            );
            self.set_state(DeviceState::Recovering(reason), out);
        }
    }

    fn disconnect(&mut self, out: &mut Vec<CanDriverOutput>) {
        if self.cycle.reset() {
            self.stats.note("cycle_cut");
        }
        self.set_state(DeviceState::Disconnected, out);
    }

    fn state(&self) -> &DeviceState {
        &self.state
    }

    fn stats(&self) -> &DeviceStats {
        &self.stats
    }

    fn named_counters(&self) -> Vec<(String, u64)> {
        self.missing
            .iter()
            .map(|(name, n)| (format!("missing_reading.{name}"), *n))
            .collect()
    }
}
