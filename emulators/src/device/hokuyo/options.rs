//! How an emulated sensor is set up: its link, start-up protocol, clock,
//! failure behaviour, measurement noise and multi-echo rate.

use crate::device::Faults;

/// The link between host and sensor.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Link {
    /// USB CDC-ACM: no bit rate; output is not paced.
    Usb,
    /// RS-232 8N1 starting (and reset by RS/reboot) at `baud`; output is
    /// paced at 10 bit times per byte and SS changes the rate once its reply
    /// has been sent (spec §8.7 note 2, p. 16). The URG-04LX ships at 19200.
    Rs232 {
        /// The power-on bit rate.
        baud: u32,
    },
}

/// Set-up of a [`HokuyoEmulator`](super::HokuyoEmulator). `Default` gives a
/// healthy USB sensor in SCIP 2.0 with datasheet noise and no dropouts.
#[derive(Debug, Clone, PartialEq)]
pub struct HokuyoOptions {
    /// Injected misbehaviour (checksum corruption, garbage bursts).
    pub faults: Faults,
    /// USB or RS-232. Default: USB.
    pub link: Link,
    /// Answer in SCIP 1.1 (every line but `SCIP2.0` gets the 1.1 error
    /// reply `E`) until `SCIP2.0` is received, at power-on and after each
    /// reboot (spec §2, p. 3). Default: false.
    pub starts_in_scip1: bool,
    /// The 24-bit millisecond clock's value at time 0 (taken modulo 2^24),
    /// to exercise its wrap. Default: 0.
    pub clock_start_ms: u32,
    /// Enter the abnormal state after this many scans have been sent: the
    /// laser goes off, a running stream ends with a `0L` message, and every
    /// command but VV/PP/II/RB is answered `0L` until RB arrives twice within
    /// one second. Happens once per emulator. Default: never.
    pub abnormal_after_scans: Option<u64>,
    /// Seed of the range noise and dropouts. Default: 0.
    pub seed: u64,
    /// Range noise as a multiple of the datasheet accuracy taken as 2 sigma
    /// (URG-04LX ±10 mm to 1 m then ±1 %; UTM-30LX ±30 mm to 10 m then
    /// ±50 mm); 0 = exact ranges. Default: 1.0.
    pub range_noise_scale: f64,
    /// Probability that a ray is lost and reported as the model's error
    /// code (below DMIN). Default: 0.
    pub dropout_probability: f64,
    /// Multi-echo scans (HD/ND/HE/NE, UTM-30LX): the probability that a
    /// step's echo is followed by a further one (its surface let part of
    /// the beam through), 0.3 to 2 m beyond it and within DMAX; a step thus
    /// has a second echo with this probability and a third with its square.
    /// Clamped to 0..=1. Default: 0.05.
    pub multi_echo_fraction: f64,
    /// Seconds the sensor is silent (and deaf) while rebooting after the
    /// second RB. Default: 1.0.
    pub reboot_seconds: f64,
}

impl Default for HokuyoOptions {
    fn default() -> Self {
        HokuyoOptions {
            faults: Faults::default(),
            link: Link::Usb,
            starts_in_scip1: false,
            clock_start_ms: 0,
            abnormal_after_scans: None,
            seed: 0,
            range_noise_scale: 1.0,
            dropout_probability: 0.0,
            multi_echo_fraction: 0.05,
            reboot_seconds: 1.0,
        }
    }
}
