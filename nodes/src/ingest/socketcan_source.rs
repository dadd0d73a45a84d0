//! SocketCAN source: a Linux CAN interface (`can0`, `vcan0`) through the
//! `socketcan` crate. Error frames (delivered only where an error mask is
//! set, which this source does not set) are skipped. Frames carry the
//! kernel's receive timestamp (`SO_TIMESTAMPNS`), taken when the frame
//! reached the socket layer, not when this node got round to reading it; a
//! frame the kernel delivered without one is dated on arrival here (counted
//! in `unstamped_frames`).

use super::device_port::host_now;
use super::{CanSource, SourceError};
use shroud_drivers::can::CanFrame;
use shroud_drivers::can_device::{FrameClock, TimedFrame};
use socketcan::{CanSocket, EmbeddedFrame, Frame, Socket, SocketOptions};
use std::io;
use std::time::{Duration, SystemTime, UNIX_EPOCH};

/// A bound raw CAN socket.
#[derive(Debug)]
pub struct SocketCanSource {
    interface: String,
    socket: CanSocket,
    /// Error frames the controller reported (bus-off, error passive, ...).
    pub error_frames: u64,
    /// Frames that came without a kernel timestamp (dated on arrival).
    pub unstamped_frames: u64,
}

impl SocketCanSource {
    /// Opens `interface` (fails with [`SourceError::Open`] if it does not exist).
    pub fn open(interface: &str) -> Result<Self, SourceError> {
        let open_error = |error| SourceError::Open {
            source_name: format!("socketcan:{interface}"),
            error,
        };
        let socket = CanSocket::open(interface).map_err(open_error)?;
        socket.set_recv_timestamp(true).map_err(open_error)?;
        Ok(Self {
            interface: interface.to_owned(),
            socket,
            error_frames: 0,
            unstamped_frames: 0,
        })
    }

    /// Sends one frame (for simulators writing to a vcan interface).
    pub fn send(&self, frame: &CanFrame) -> io::Result<()> {
        self.socket.write_frame(&to_socketcan(frame)?)
    }
}

impl CanSource for SocketCanSource {
    fn recv(&mut self, timeout: Duration) -> Result<Option<TimedFrame>, SourceError> {
        let read = self
            .socket
            .set_read_timeout(timeout.max(Duration::from_millis(1)))
            .and_then(|()| self.socket.read_frame_with_timestamps());
        match read {
            Ok((frame, stamps)) => {
                let received = host_now();
                let Some(ours) = from_socketcan(&frame) else {
                    self.error_frames += 1;
                    tracing::debug!(interface = %self.interface, "CAN error frame: {frame:?}");
                    return Ok(None);
                };
                let stamp_ns = match stamps.socket.and_then(epoch_ns) {
                    Some(ns) => ns,
                    None => {
                        self.unstamped_frames += 1;
                        received.unix_ns
                    }
                };
                Ok(Some(TimedFrame {
                    frame: ours,
                    stamp_ns,
                    clock: FrameClock::Kernel,
                    received,
                }))
            }
            Err(e)
                if matches!(
                    e.kind(),
                    io::ErrorKind::TimedOut
                        | io::ErrorKind::WouldBlock
                        | io::ErrorKind::Interrupted
                ) =>
            {
                Ok(None)
            }
            Err(error) => Err(SourceError::Disconnected {
                source_name: self.name(),
                error,
            }),
        }
    }

    fn send(&mut self, frame: &CanFrame) -> Result<(), SourceError> {
        SocketCanSource::send(self, frame).map_err(|error| SourceError::Disconnected {
            source_name: self.name(),
            error,
        })
    }

    fn writable(&self) -> bool {
        true
    }

    fn name(&self) -> String {
        format!("socketcan:{}", self.interface)
    }
}

/// A kernel stamp as ns since the epoch (`SystemTime` is what the crate gives).
fn epoch_ns(t: SystemTime) -> Option<u64> {
    t.duration_since(UNIX_EPOCH)
        .ok()
        .map(|d| d.as_nanos() as u64)
}

/// Our frame from a socketcan one; `None` for an error frame.
pub fn from_socketcan(frame: &socketcan::CanFrame) -> Option<CanFrame> {
    let (id, extended) = (frame.raw_id(), frame.is_extended());
    match frame {
        socketcan::CanFrame::Data(_) => CanFrame::new(id, extended, frame.data()).ok(),
        socketcan::CanFrame::Remote(_) => CanFrame::remote(id, extended, frame.dlc() as u8).ok(),
        socketcan::CanFrame::Error(_) => None,
    }
}

/// A socketcan frame from ours.
pub fn to_socketcan(frame: &CanFrame) -> io::Result<socketcan::CanFrame> {
    let id: socketcan::Id = if frame.extended {
        socketcan::ExtendedId::new(frame.id).map(Into::into)
    } else {
        u16::try_from(frame.id)
            .ok()
            .and_then(socketcan::StandardId::new)
            .map(Into::into)
    }
    .ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "CAN id out of range"))?;
    let built = if frame.remote {
        socketcan::CanFrame::new_remote(id, frame.len.into())
    } else {
        socketcan::CanFrame::new(id, frame.payload())
    };
    built.ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "bad CAN frame"))
}
