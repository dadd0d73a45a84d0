//! A received CAN frame with its two times: when the frame was on the bus
//! (as well as the transport can tell) and when this host's node read it.

use super::super::can::CanFrame;
use super::super::device::HostTime;

/// Where a frame's `stamp_ns` comes from, per transport: stated in the
/// status so that a user knows what a cloud's stamp means.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrameClock {
    /// The kernel's receive timestamp (SocketCAN `SO_TIMESTAMPNS`).
    Kernel,
    /// The stamp written in a candump log at recording time.
    Log,
    /// The host's wall clock when the read that returned the frame's bytes
    /// completed (SLCAN adapters; an in-memory bus).
    HostReceipt,
}

impl FrameClock {
    /// A stable lower-case name for labels and logs.
    pub fn name(self) -> &'static str {
        match self {
            Self::Kernel => "kernel",
            Self::Log => "log",
            Self::HostReceipt => "host-receipt",
        }
    }
}

/// One received frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimedFrame {
    pub frame: CanFrame,
    /// When the frame was on the bus, ns since the Unix epoch, on the clock
    /// `clock` names. Becomes the stamp of the cloud it starts.
    pub stamp_ns: u64,
    pub clock: FrameClock,
    /// When this node read it, on the host's own clocks: ages and timeouts
    /// are measured from here, never from `stamp_ns`.
    pub received: HostTime,
}
