//! A USB SLCAN (Lawicel ASCII) adapter with a CAN device on its bus: to the
//! host a serial device that answers `Sn`, `O`, `C` and `V` and carries frames
//! as `t`/`T` lines both ways, to the CAN device a bus. Frames flow only while
//! the channel is open, at the bitrate the device runs at: at another rate the
//! adapter hears nothing it can decode (as a real one would), and says so in
//! its `bitrate_mismatch` count.

use crate::can_device::CanDeviceEmulator;
use crate::device::SerialDeviceEmulator;
use shroud_drivers::can::slcan::{write_frame, SlcanDecoder, SlcanMessage};

/// The adapter and the device on its bus.
pub struct SlcanAdapter {
    device: Box<dyn CanDeviceEmulator>,
    /// The bus's bitrate (what the device runs at).
    bus_bitrate: u32,
    decoder: SlcanDecoder,
    /// The bitrate the host asked for with `Sn` (none yet: the adapter's
    /// power-up default, taken to be the bus's).
    host_bitrate: Option<u32>,
    open: bool,
    replies: Vec<u8>,
    frames: Vec<(f64, shroud_drivers::can::CanFrame)>,
    /// Frames the device sent that the host could not get: channel closed or
    /// at the wrong bitrate.
    pub frames_unheard: u64,
    pub bitrate_mismatch: u64,
}

impl SlcanAdapter {
    pub fn new(device: Box<dyn CanDeviceEmulator>, bus_bitrate: u32) -> Self {
        Self {
            device,
            bus_bitrate,
            decoder: SlcanDecoder::default(),
            host_bitrate: None,
            open: false,
            replies: Vec::new(),
            frames: Vec::new(),
            frames_unheard: 0,
            bitrate_mismatch: 0,
        }
    }

    fn bitrate_matches(&self) -> bool {
        self.host_bitrate.is_none_or(|b| b == self.bus_bitrate)
    }

    /// One host line: commands answered `\r` (OK) or `\x07` (refused), as
    /// the Lawicel protocol does.
    fn command(&mut self, message: SlcanMessage, now: f64) {
        let ok = match message {
            SlcanMessage::Bitrate(bps) if !self.open => {
                self.host_bitrate = Some(bps);
                true
            }
            SlcanMessage::Open { .. } if !self.open => {
                self.open = true;
                true
            }
            SlcanMessage::Close => {
                self.open = false;
                true
            }
            SlcanMessage::Frame { frame, .. } if self.open && self.bitrate_matches() => {
                self.device.receive(&frame, now);
                // `t`/`T` are acknowledged with `z`/`Z` (Lawicel: "transmit ok").
                self.replies
                    .extend_from_slice(if frame.extended { b"Z" } else { b"z" });
                true
            }
            SlcanMessage::Other(text) if text == "V" => {
                self.replies.extend_from_slice(b"V1013");
                true
            }
            SlcanMessage::Ack => true,
            _ => false,
        };
        self.replies.push(if ok { b'\r' } else { 0x07 });
    }
}

impl SerialDeviceEmulator for SlcanAdapter {
    fn model(&self) -> &'static str {
        self.device.model()
    }

    fn receive(&mut self, bytes: &[u8], now: f64) {
        for message in self.decoder.push(bytes) {
            match message {
                Ok(message) => self.command(message, now),
                Err(_) => self.replies.push(0x07),
            }
        }
    }

    fn poll(&mut self, now: f64, out: &mut Vec<u8>) {
        out.append(&mut self.replies);
        self.frames.clear();
        self.device.poll(now, &mut self.frames);
        let heard = self.open && self.bitrate_matches();
        if !heard {
            self.frames_unheard += self.frames.len() as u64;
            if self.open {
                self.bitrate_mismatch += self.frames.len() as u64;
            }
            return;
        }
        for (_, frame) in &self.frames {
            write_frame(frame, out);
        }
    }

    /// A USB CDC device: the host's baud rate does not matter.
    fn uart_baud(&self) -> Option<u32> {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use shroud_drivers::can::CanFrame;

    /// A device that sends one frame every poll and remembers what it got.
    struct Echo {
        got: Vec<CanFrame>,
    }

    impl CanDeviceEmulator for Echo {
        fn model(&self) -> &'static str {
            "echo"
        }
        fn receive(&mut self, frame: &CanFrame, _now: f64) {
            self.got.push(*frame);
        }
        fn poll(&mut self, now: f64, out: &mut Vec<(f64, CanFrame)>) {
            out.push((now, CanFrame::new(0x201, false, &[1, 2]).unwrap()));
        }
    }

    #[test]
    fn frames_flow_only_through_an_open_channel_at_the_bus_bitrate() {
        let mut adapter = SlcanAdapter::new(Box::new(Echo { got: Vec::new() }), 500_000);
        let mut out = Vec::new();
        adapter.poll(0.0, &mut out);
        assert!(out.is_empty(), "closed channel");
        adapter.receive(b"C\rS8\rO\r", 0.0);
        out.clear();
        adapter.poll(0.1, &mut out);
        assert_eq!(
            out, b"\r\r\r",
            "1 Mbit/s on a 500 kbit/s bus: nothing decodable"
        );
        assert_eq!(adapter.bitrate_mismatch, 1);
        adapter.receive(b"C\rS6\rO\rt2001AB\rX\r", 0.2);
        out.clear();
        adapter.poll(0.3, &mut out);
        assert_eq!(out, b"\r\r\rz\r\x07t20120102\r");
    }
}
