//! SLCAN source: a Lawicel ASCII CAN adapter on a serial port. On open it sends
//! `C`, `Sn`, `O` (close, bitrate, open); on drop it sends `C`. Frames are
//! dated by the host's clock when the read that returned them completed.

use super::can_source::received_now;
use super::{CanSource, SourceError};
use shroud_drivers::can::slcan::{encode_frame, open_commands, SlcanDecoder, SlcanMessage};
use shroud_drivers::can::CanFrame;
use shroud_drivers::can_device::TimedFrame;
use shroud_drivers::DecoderStats;
use std::collections::VecDeque;
use std::io::{self, Read, Write};
use std::time::{Duration, Instant};

/// An open SLCAN adapter.
pub struct SlcanSource {
    path: String,
    port: Box<dyn serialport::SerialPort>,
    decoder: SlcanDecoder,
    pending: VecDeque<TimedFrame>,
}

impl std::fmt::Debug for SlcanSource {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SlcanSource")
            .field("path", &self.path)
            .finish_non_exhaustive()
    }
}

impl SlcanSource {
    /// Opens the adapter at `path` (`baud` is the serial rate, irrelevant for
    /// USB adapters) and, if `bitrate` is given, sets the CAN bitrate and opens
    /// the channel. Without `bitrate` nothing is sent (a listen-only tap, or a
    /// simulator that streams unasked).
    pub fn open(path: &str, baud: u32, bitrate: Option<u32>) -> Result<Self, SourceError> {
        let open_error = |error: io::Error| SourceError::Open {
            source_name: format!("slcan:{path}"),
            error,
        };
        let mut port = serialport::new(path, baud)
            .timeout(Duration::from_millis(50))
            .open()
            .map_err(|e| open_error(e.into()))?;
        if let Some(bitrate) = bitrate {
            let commands = open_commands(bitrate)
                .map_err(|e| SourceError::Fatal(format!("slcan:{path}: {e}")))?;
            port.write_all(&commands).map_err(open_error)?;
        }
        Ok(Self {
            path: path.to_owned(),
            port,
            decoder: SlcanDecoder::default(),
            pending: VecDeque::new(),
        })
    }

    fn disconnected(&self, error: io::Error) -> SourceError {
        SourceError::Disconnected {
            source_name: self.name(),
            error,
        }
    }
}

impl CanSource for SlcanSource {
    fn recv(&mut self, timeout: Duration) -> Result<Option<TimedFrame>, SourceError> {
        let deadline = Instant::now() + timeout;
        let mut buf = [0u8; 1024];
        loop {
            if let Some(frame) = self.pending.pop_front() {
                return Ok(Some(frame));
            }
            let left = deadline.saturating_duration_since(Instant::now());
            if left.is_zero() {
                return Ok(None);
            }
            self.port
                .set_timeout(left.max(Duration::from_millis(1)))
                .map_err(|e| self.disconnected(e.into()))?;
            let n = match self.port.read(&mut buf) {
                Ok(0) => return Err(self.disconnected(io::ErrorKind::UnexpectedEof.into())),
                Ok(n) => n,
                Err(e)
                    if matches!(
                        e.kind(),
                        io::ErrorKind::TimedOut
                            | io::ErrorKind::WouldBlock
                            | io::ErrorKind::Interrupted
                    ) =>
                {
                    return Ok(None)
                }
                Err(e) => return Err(self.disconnected(e)),
            };
            for message in self.decoder.push(&buf[..n]) {
                match message {
                    Ok(SlcanMessage::Frame { frame, .. }) => {
                        self.pending.push_back(received_now(frame))
                    }
                    Ok(other) => tracing::trace!(path = %self.path, "slcan: {other:?}"),
                    Err(error) => tracing::debug!(path = %self.path, "slcan: {error}"),
                }
            }
        }
    }

    fn send(&mut self, frame: &CanFrame) -> Result<(), SourceError> {
        let line = encode_frame(frame);
        self.port.write_all(&line).map_err(|e| self.disconnected(e))
    }

    fn writable(&self) -> bool {
        true
    }

    fn name(&self) -> String {
        format!("slcan:{}", self.path)
    }

    fn transport_stats(&self) -> DecoderStats {
        *self.decoder.stats()
    }
}

impl Drop for SlcanSource {
    fn drop(&mut self) {
        let _ = self.port.write_all(b"C\r");
    }
}
