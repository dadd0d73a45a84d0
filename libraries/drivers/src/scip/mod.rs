//! Hokuyo SCIP 2.0 laser range finders (URG-04LX, and other SCIP 2.0 sensors
//! over USB CDC-ACM or RS-232), sans-I/O: codec pieces (character encoding,
//! line sums, commands, line splitting, reply assembly, parameter replies,
//! scan data, multi-echo data), the sensor clock, and [`ScipDriver`], the
//! state machine that probes, configures and streams.
//!
//! Measurement commands: `MD`/`MS`/`ME` streamed and `GD`/`GE` polled
//! (ranges, 2-character ranges, ranges with intensity), and the multi-echo
//! `ND`/`NE` streamed and `HD`/`HE` polled (ranges, ranges with intensity;
//! up to 3 echoes per step, each after the first prefixed `&` in the data,
//! urg_c `receive_length_data()`). A refused multi-echo command falls back to
//! `MD`/`ME`/`GD`/`GE`, a refused intensity command to `MD`/`GD`.
//!
//! Sources: Hokuyo "Communication Protocol Specification for SCIP2.0"
//! (C-42-03320B, cited as "spec §n"), ros-drivers/urg_c `current/src/*.c` at
//! bbe007f5, ros-drivers/urg_node `src/urg_c_wrapper.cpp` at 369ee4d,
//! seqsense/urg_stamped `src/urg_stamped.cpp` at a92e831; summarised in
//! shared/research/sensors.md §1.1.
//!
//! Conventions (REP-103): a ray's angle is `(step - AFRT) * 2π / ARES`
//! radians, counter-clockwise positive from the sensor's front, since the
//! beam turns counter-clockwise seen from above (spec §5). With cluster `c`,
//! value `i` of a scan carries the angle and time of step `start + i*c`, the
//! first step of its cluster; a value is one ray, except that every echo of a
//! multi-echo value is a ray of its own with that angle and time, first echo
//! first (so a multi-echo scan has between one and three rays per value).
//! Ranges below `DMIN` (error codes) or above `DMAX` are NaN rays, kept
//! (multi-echo included: no echo is dropped, none is invented). A ray's `offset_ns` is its step distance from the first ray
//! times 60e9 / (`SCAN` * `ARES`) ns. A scan's `stamp_ns` is the first ray's
//! time: the sensor timestamp mapped through the `TM1` clock offset, plus the
//! time the beam takes from the rear centre (the instant the timestamp is
//! assumed to mark, see [`first_ray_delay_ns`]) to the first ray.

mod clock;
mod command;
mod config;
mod driver;
mod echoes;
mod encoding;
mod handshake;
mod line;
mod params;
mod rays;
mod reply;
mod scan_data;
mod scan_error;
mod status;
mod streaming;
mod sum;

#[cfg(test)]
mod tests;

pub use clock::{
    ClockSync, DeviceClock, ScanStamper, ScanTiming, MAX_DRIFT_PPM, MAX_STAMP_LAG_NS,
    MAX_STAMP_LEAD_NS, WRAP_MS,
};
pub use command::{Command, CommandError, ScanKind, ScanRequest, Tag, TimeMode, MAX_ECHOES};
pub use config::{Link, ScanCommand, ScipConfig};
pub use driver::ScipDriver;
pub use echoes::ECHO_MARK;
pub use encoding::{decode, encode};
pub use line::{LineEvent, LineSplitter, MAX_LINE_LEN};
pub use params::{health, parse_pairs, ParamError, ScipGeometry};
pub use rays::{first_ray_delay_ns, ScanPlan};
pub use reply::{Assembled, Reply, ReplyAssembler, MAX_REPLY_LINES};
pub use scan_data::{decode_scan, decode_timestamp, ScanData};
pub use scan_error::ScanDataError;
pub use status::{Status, StatusClass, StatusLineError};
pub use sum::{line_sum, strip_parameter_sum, strip_sum};
