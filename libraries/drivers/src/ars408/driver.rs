//! The ARS408 driver: frames in, clouds, health, identity and configuration
//! frames out ([`CanDeviceDriver`]).

use super::cloud::cycle_cloud;
use super::config::{Ars408Config, RadarOutput};
use super::configure::{Configurator, Progress, Retry};
use super::cycle::{
    CompleteCycle, CycleAssembler, Expect, IdRule, Loss, Status, MAX_CLUSTERS, MAX_OBJECTS,
};
use super::error::Ars408Error;
use super::layout::{code, Layout, RadarMessage, Section};
use super::radar_state::{output_type_name, version_identity, RadarState};
use crate::can_device::{CanDeviceDriver, CanDriverOutput, TimedFrame};
use crate::dbc::CanDatabase;
use crate::device::{DeviceState, DeviceStats, HostTime};

/// One ARS408-21 on a bus.
#[derive(Debug, Clone)]
pub struct Ars408Driver {
    config: Ars408Config,
    layout: Layout,
    configurator: Option<Configurator>,
    assembler: CycleAssembler,
    state: DeviceState,
    stats: DeviceStats,
    connected_at: HostTime,
    /// When the last radar frame was read (host time).
    last_frame: Option<HostTime>,
    silent: bool,
    /// Streaming reached since the last connect (counts a handshake once).
    streamed: bool,
    radar: Option<RadarState>,
    version: Vec<(String, String)>,
    identity_sent: Option<Vec<(String, String)>>,
    health_sent: Option<(bool, String)>,
    /// What the radar did not take of the configuration, after giving up.
    config_problem: Option<String>,
}

impl Ars408Driver {
    /// A driver for the radar `config` describes, reading `database` (the
    /// builtin `dbc::builtin("ars408")` or a user's variant, for sensor id 0:
    /// the driver moves its ids by 0x10 * `sensor_id`). Fails on a bad
    /// setting, or when the database lacks a message or signal the driver
    /// uses for this output (and RadarConfiguration when settings are given).
    pub fn new(config: Ars408Config, database: CanDatabase) -> Result<Self, Ars408Error> {
        config.validate()?;
        let delta = 0x10 * u32::from(config.sensor_id);
        let database = database
            .with_id_offset(delta)
            .map_err(|source| Ars408Error::IdOffset {
                sensor_id: config.sensor_id,
                source,
            })?;
        let layout = Layout::new(&database, config.output, config.settings.is_some())?;
        let configurator = match (&layout.configuration, config.settings) {
            (Some(bound), Some(settings)) => {
                Some(Configurator::new(bound, config.output, settings)?)
            }
            _ => None,
        };
        let assembler = match config.output {
            RadarOutput::Clusters => {
                let bits = layout
                    .cycle
                    .general
                    .spec
                    .signal("ID")
                    .map_or(8, |s| u32::from(s.size));
                let modulus = if bits >= 32 { u32::MAX } else { 1 << bits };
                CycleAssembler::new(IdRule::Sequential { modulus }, MAX_CLUSTERS)
            }
            RadarOutput::Objects => CycleAssembler::new(IdRule::Tracked, MAX_OBJECTS),
        };
        Ok(Self {
            config,
            layout,
            configurator,
            assembler,
            state: DeviceState::Disconnected,
            stats: DeviceStats::default(),
            connected_at: HostTime::default(),
            last_frame: None,
            silent: false,
            streamed: false,
            radar: None,
            version: Vec::new(),
            identity_sent: None,
            health_sent: None,
            config_problem: None,
        })
    }

    pub fn config(&self) -> &Ars408Config {
        &self.config
    }

    /// The state this driver would be in were the radar not silent.
    fn running_state(&self) -> DeviceState {
        if self
            .configurator
            .as_ref()
            .is_some_and(Configurator::waiting)
        {
            DeviceState::Configuring
        } else if self.last_frame.is_some() {
            DeviceState::Streaming
        } else {
            DeviceState::Connecting
        }
    }

    fn set_state(&mut self, state: DeviceState, out: &mut Vec<CanDriverOutput>) {
        if state == DeviceState::Streaming && !self.streamed {
            self.streamed = true;
            self.stats.handshakes += 1;
        }
        if self.state != state {
            self.state = state.clone();
            out.push(CanDriverOutput::State(state));
        }
    }

    fn send(&mut self, frame: crate::can::CanFrame, out: &mut Vec<CanDriverOutput>) {
        self.stats.commands += 1;
        out.push(CanDriverOutput::Send(frame));
    }

    /// Health = the radar's error bits and, after a configuration that did
    /// not take, what did not; reported when it changes.
    fn report_health(&mut self, out: &mut Vec<CanDriverOutput>) {
        let errors = self.radar.map(|r| r.error_names()).unwrap_or_default();
        // A radar sending the other list publishes nothing this driver reads:
        // that is a fault, whether or not this driver configures it.
        let wanted = self.config.output;
        let other_output = self
            .radar
            .filter(|r| r.output_type != wanted.code())
            .map(|r| {
                format!(
                    "the radar outputs {}, this driver reads {}",
                    output_type_name(r.output_type),
                    wanted.name()
                )
            });
        let ok = errors.is_empty() && self.config_problem.is_none() && other_output.is_none();
        let mut parts: Vec<String> = errors.iter().map(|e| (*e).to_owned()).collect();
        parts.extend(self.config_problem.clone());
        parts.extend(other_output);
        let detail = if parts.is_empty() {
            "no errors".to_owned()
        } else {
            parts.join("; ")
        };
        if self.health_sent.as_ref() != Some(&(ok, detail.clone())) {
            self.health_sent = Some((ok, detail.clone()));
            out.push(CanDriverOutput::Health { ok, detail });
        }
    }

    /// Identity = VersionID's pairs then the configuration RadarState
    /// reports; reported when it changes.
    fn report_identity(&mut self, out: &mut Vec<CanDriverOutput>) {
        let mut pairs = self.version.clone();
        pairs.extend(self.radar.map(|r| r.identity()).unwrap_or_default());
        if self.identity_sent.as_ref() != Some(&pairs) {
            self.identity_sent = Some(pairs.clone());
            out.push(CanDriverOutput::Identity(pairs));
        }
    }

    fn on_radar_state(
        &mut self,
        frame: &TimedFrame,
        done: &mut Vec<CompleteCycle>,
        out: &mut Vec<CanDriverOutput>,
    ) {
        let decoded = self.layout.radar_state.read(&frame.frame).ok();
        let Some(state) = decoded.as_ref().and_then(RadarState::from_values) else {
            self.stats.count("bad_frame");
            return;
        };
        let id_differs = state.sensor_id != u32::from(self.config.sensor_id);
        if id_differs && self.radar.is_none_or(|r| r.sensor_id != state.sensor_id) {
            // Once per change: the state comes 20 times a second.
            self.stats.count("sensor_id_mismatch");
        }
        self.radar = Some(state);
        self.assembler
            .radar_says(state.send_quality, state.send_ext_info, done);
        if let Some(configurator) = &mut self.configurator {
            let matches = configurator.mismatches(&state).is_empty();
            let settled = matches!(
                configurator.progress,
                Progress::Waiting { .. } | Progress::GaveUp
            );
            if matches && settled {
                configurator.progress = Progress::Confirmed;
                self.config_problem = None;
                self.stats.note("config_confirmed");
            } else if !matches && configurator.progress == Progress::Confirmed {
                // It reported what it was told, and no longer does: it
                // restarted with its stored settings (they are not stored in
                // its NVM). Configure it again, and confirm again.
                self.stats.count("config_lost");
                let again = configurator.start(frame.received);
                self.send(again, out);
            }
        }
        self.report_health(out);
        self.report_identity(out);
    }

    fn on_status(&mut self, frame: &TimedFrame, done: &mut Vec<CompleteCycle>) {
        let objects = self.config.output == RadarOutput::Objects;
        let status = self
            .layout
            .cycle
            .status
            .read(&frame.frame)
            .ok()
            .and_then(|[near, far, counter]| {
                let near = code(near)? as usize;
                let far = if objects { 0 } else { code(far)? as usize };
                Some(Status {
                    count: near.checked_add(far)?,
                    meas_counter: code(counter)?,
                    stamp_ns: frame.stamp_ns,
                    received: frame.received,
                })
            })
            .ok_or(Loss::Bad);
        let quality = Expect::from_flag(self.radar.map(|r| r.send_quality));
        let extended = if objects {
            Expect::from_flag(self.radar.map(|r| r.send_ext_info))
        } else {
            Expect::No
        };
        self.assembler
            .status(status, quality, extended, &mut self.stats, done);
    }

    fn on_follow_up(
        &mut self,
        section: Section,
        frame: &TimedFrame,
        done: &mut Vec<CompleteCycle>,
    ) {
        let c = &self.layout.cycle;
        let values: Result<Vec<f64>, Loss> = match section {
            Section::General => c.general.read(&frame.frame).map(|v| v.to_vec()),
            Section::Quality => c.quality.read(&frame.frame).map(|v| v.to_vec()),
            Section::Extended => match &c.extended {
                Some(b) => b.read(&frame.frame).map(|v| v.to_vec()),
                None => return,
            },
        }
        .map_err(|_| Loss::Bad);
        self.assembler.follow_up(
            section,
            values.as_deref().map_err(|l| *l),
            &mut self.stats,
            done,
        );
    }
}

impl CanDeviceDriver for Ars408Driver {
    fn kind(&self) -> &'static str {
        "ars408"
    }

    fn connect(&mut self, now: HostTime, writable: bool, out: &mut Vec<CanDriverOutput>) {
        if self.assembler.reset() {
            self.stats.note("cycle_cut");
        }
        self.connected_at = now;
        self.last_frame = None;
        self.silent = false;
        self.streamed = false;
        self.radar = None;
        self.version.clear();
        self.identity_sent = None;
        self.health_sent = None;
        self.config_problem = None;
        let mut first = None;
        if let Some(configurator) = &mut self.configurator {
            if writable {
                first = Some(configurator.start(now));
            } else {
                configurator.stop();
                self.stats.note("config_not_sent");
            }
        }
        if let Some(frame) = first {
            self.send(frame, out);
        }
        let state = self.running_state();
        self.set_state(state, out);
    }

    fn receive(&mut self, frame: &TimedFrame, out: &mut Vec<CanDriverOutput>) {
        let f = &frame.frame;
        self.stats.bytes += f.payload().len() as u64;
        let message = self.layout.message_of(f.id);
        if message.is_some() && (f.extended || f.remote) {
            // The radar sends only standard data frames (sensors.md §2.2).
            self.stats.count("bad_frame");
            return;
        }
        let Some(message) = message else {
            let other_output =
                !f.extended && !f.remote && self.layout.other_output_ids.contains(&f.id);
            if other_output {
                self.stats.note("other_output");
                self.alive(frame.received, out);
            } else {
                self.stats.note("other_id");
            }
            return;
        };
        self.alive(frame.received, out);
        let mut done = Vec::new();
        match message {
            RadarMessage::State => self.on_radar_state(frame, &mut done, out),
            RadarMessage::Version => {
                match self
                    .layout
                    .version
                    .read(f)
                    .ok()
                    .as_ref()
                    .and_then(version_identity)
                {
                    Some(pairs) => {
                        self.version = pairs;
                        self.report_identity(out);
                    }
                    None => self.stats.count("bad_frame"),
                }
            }
            RadarMessage::Status => self.on_status(frame, &mut done),
            RadarMessage::FollowUp(section) => self.on_follow_up(section, frame, &mut done),
        }
        // A RadarState may have confirmed the configuration.
        let state = self.running_state();
        self.set_state(state, out);
        for cycle in &done {
            self.stats.scans += 1;
            let cloud = cycle_cloud(cycle, self.config.output, &self.config.mount);
            out.push(CanDriverOutput::Cloud(cloud));
        }
    }

    fn poll(&mut self, now: HostTime, out: &mut Vec<CanDriverOutput>) {
        if self.state == DeviceState::Disconnected {
            return;
        }
        let retry = self
            .configurator
            .as_mut()
            .map_or(Retry::Nothing, |c| c.poll(now));
        match retry {
            Retry::Nothing => {}
            Retry::Resend(frame) => self.send(frame, out),
            Retry::GiveUp => {
                self.stats.count("config_not_confirmed");
                let detail = match (&self.configurator, &self.radar) {
                    (Some(c), Some(state)) => c.mismatches(state).join(", "),
                    _ => "no RadarState received".to_owned(),
                };
                self.config_problem = Some(format!("configuration not confirmed: {detail}"));
                self.report_health(out);
                if !self.silent {
                    let state = self.running_state();
                    self.set_state(state, out);
                }
            }
        }
        let since = self.last_frame.unwrap_or(self.connected_at);
        let quiet = now.since(since);
        if !self.silent && quiet >= self.config.silence_timeout_ns {
            self.silent = true;
            self.stats.count("silent");
            let reason = format!("no frames from the radar for {:.1} s", quiet as f64 * 1e-9);
            self.set_state(DeviceState::Recovering(reason), out);
        }
    }

    fn disconnect(&mut self, out: &mut Vec<CanDriverOutput>) {
        if self.assembler.reset() {
            self.stats.note("cycle_cut");
        }
        if let Some(c) = &mut self.configurator {
            c.stop();
        }
        self.set_state(DeviceState::Disconnected, out);
    }

    fn state(&self) -> &DeviceState {
        &self.state
    }

    fn stats(&self) -> &DeviceStats {
        &self.stats
    }
}

impl Ars408Driver {
    /// A radar frame was read: the radar is not silent (any more).
    fn alive(&mut self, received: HostTime, out: &mut Vec<CanDriverOutput>) {
        self.last_frame = Some(received);
        self.silent = false;
        let state = self.running_state();
        self.set_state(state, out);
    }
}
