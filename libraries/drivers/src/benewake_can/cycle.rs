//! One cycle of the rangefinders on a bus: it starts at the first reading
//! after the last cloud and closes when every sensor has reported once, when
//! a sensor reports a second time (the cycle closes without the others, and
//! the reading starts the next), or when the cycle timeout passes.

use crate::device::HostTime;

/// What one sensor reported in a cycle: its point (robot frame) if valid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Report {
    pub point: Option<[f32; 3]>,
    pub strength: u32,
    pub device_time_ms: Option<u32>,
}

/// A closed cycle: one slot per configured sensor, `None` for the missing.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct ClosedCycle {
    pub stamp_ns: u64,
    pub received: HostTime,
    pub reports: Vec<Option<Report>>,
}

impl ClosedCycle {
    /// The indices of the sensors that did not report.
    pub fn missing(&self) -> impl Iterator<Item = usize> + '_ {
        self.reports
            .iter()
            .enumerate()
            .filter_map(|(k, r)| r.is_none().then_some(k))
    }
}

#[derive(Debug, Clone, PartialEq)]
pub(super) struct CycleBuilder {
    sensors: usize,
    open: Option<ClosedCycle>,
}

impl CycleBuilder {
    pub fn new(sensors: usize) -> Self {
        Self {
            sensors,
            open: None,
        }
    }

    /// Drops the open cycle; `true` if there was one.
    pub fn reset(&mut self) -> bool {
        self.open.take().is_some()
    }

    /// Sensor `sensor`'s reading, read at `received` and stamped
    /// `stamp_ns`; closed cycles go to `done` (at most two: the one this
    /// reading could not join, and the one it completed).
    pub fn add(
        &mut self,
        sensor: usize,
        report: Report,
        stamp_ns: u64,
        received: HostTime,
        done: &mut Vec<ClosedCycle>,
    ) {
        let repeat = self
            .open
            .as_ref()
            .is_some_and(|c| c.reports.get(sensor).is_some_and(Option::is_some));
        if repeat {
            done.extend(self.open.take());
        }
        let sensors = self.sensors;
        let cycle = self.open.get_or_insert_with(|| ClosedCycle {
            stamp_ns,
            received,
            reports: vec![None; sensors],
        });
        if let Some(slot) = cycle.reports.get_mut(sensor) {
            *slot = Some(report);
        }
        if cycle.reports.iter().all(Option::is_some) {
            done.extend(self.open.take());
        }
    }

    /// The open cycle, if its first reading is `timeout_ns` old at `now`.
    pub fn poll(&mut self, now: HostTime, timeout_ns: u64) -> Option<ClosedCycle> {
        let expired = self
            .open
            .as_ref()
            .is_some_and(|c| now.since(c.received) >= timeout_ns);
        if expired {
            self.open.take()
        } else {
            None
        }
    }
}
