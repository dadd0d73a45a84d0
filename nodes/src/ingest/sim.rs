//! Writers for simulated sensors: scans as serial protocol frames, as SLCAN
//! lines, or as a candump log, to any `Write` (a pty master, a serial port, a
//! file). A writer never blocks for long: bytes a full device will not take
//! within the patience are dropped and counted, as on a real UART.

use shroud_drivers::can::{format_candump_line, slcan, CanFrame, CanSensorConfig, CandumpRecord};
use shroud_drivers::serial::SerialEncoder;
use shroud_drivers::Scan;
use std::io::{self, Write};
use std::time::{Duration, Instant};

/// Something that takes whole scans.
pub trait ScanSink {
    /// Writes one scan. I/O errors other than "device full" are returned.
    fn write_scan(&mut self, scan: &Scan) -> anyhow::Result<()>;
    /// Bytes (or, for a log, lines) dropped because the device was full.
    fn dropped(&self) -> u64 {
        0
    }
}

/// Writes all of `bytes`, retrying while the device is full for at most
/// `patience`; returns how many bytes were written (less than all if it gave up).
pub fn write_with_patience(
    out: &mut dyn Write,
    bytes: &[u8],
    patience: Duration,
) -> io::Result<usize> {
    let deadline = Instant::now() + patience;
    let mut written = 0;
    while written < bytes.len() {
        match out.write(&bytes[written..]) {
            Ok(0) => return Err(io::ErrorKind::WriteZero.into()),
            Ok(n) => written += n,
            Err(e)
                if matches!(
                    e.kind(),
                    io::ErrorKind::WouldBlock
                        | io::ErrorKind::TimedOut
                        | io::ErrorKind::Interrupted
                ) =>
            {
                if Instant::now() >= deadline {
                    break;
                }
                std::thread::sleep(Duration::from_millis(1));
            }
            Err(e) => return Err(e),
        }
    }
    Ok(written)
}

/// A serial range sensor: every scan as protocol frames (`docs/sensor-protocols.md` §1).
pub struct SerialSensorWriter<W: Write> {
    pub out: W,
    pub encoder: SerialEncoder,
    pub patience: Duration,
    /// Bytes the device would not take.
    pub dropped_bytes: u64,
    /// Corrupt every n-th scan (garbage before it, one byte flipped); 0 = never.
    pub corrupt_every: u64,
    scans: u64,
}

impl<W: Write> SerialSensorWriter<W> {
    pub fn new(out: W, encoder: SerialEncoder) -> Self {
        Self {
            out,
            encoder,
            patience: Duration::from_millis(200),
            dropped_bytes: 0,
            corrupt_every: 0,
            scans: 0,
        }
    }

    /// Writes raw bytes (for tests injecting their own faults).
    pub fn write_raw(&mut self, bytes: &[u8]) -> io::Result<()> {
        let n = write_with_patience(&mut self.out, bytes, self.patience)?;
        self.dropped_bytes += (bytes.len() - n) as u64;
        self.out.flush()
    }
}

impl<W: Write> ScanSink for SerialSensorWriter<W> {
    fn write_scan(&mut self, scan: &Scan) -> anyhow::Result<()> {
        let mut bytes = self.encoder.encode(scan)?;
        self.scans += 1;
        if self.corrupt_every > 0 && self.scans.is_multiple_of(self.corrupt_every) {
            let mid = bytes.len() / 2;
            bytes[mid] ^= 0xFF;
            bytes.splice(0..0, *b"\x00garbage\xA5");
        }
        self.write_raw(&bytes)?;
        Ok(())
    }

    fn dropped(&self) -> u64 {
        self.dropped_bytes
    }
}

/// An SLCAN adapter on the bus of a CAN range sensor: every scan as `t`/`T` lines.
pub struct SlcanWriter<W: Write> {
    pub out: W,
    pub sensor: CanSensorConfig,
    pub patience: Duration,
    pub dropped_bytes: u64,
    /// Corrupt every n-th scan (a garbage line, one hex digit broken); 0 = never.
    pub corrupt_every: u64,
    scans: u64,
}

impl<W: Write> SlcanWriter<W> {
    pub fn new(out: W, sensor: CanSensorConfig) -> Self {
        Self {
            out,
            sensor,
            patience: Duration::from_millis(200),
            dropped_bytes: 0,
            corrupt_every: 0,
            scans: 0,
        }
    }

    /// Writes frames as SLCAN lines.
    pub fn write_frames(&mut self, frames: &[CanFrame]) -> io::Result<()> {
        let mut bytes = Vec::with_capacity(frames.len() * 22);
        for f in frames {
            slcan::write_frame(f, &mut bytes);
        }
        self.write_raw(&bytes)
    }

    pub fn write_raw(&mut self, bytes: &[u8]) -> io::Result<()> {
        let n = write_with_patience(&mut self.out, bytes, self.patience)?;
        self.dropped_bytes += (bytes.len() - n) as u64;
        self.out.flush()
    }
}

impl<W: Write> ScanSink for SlcanWriter<W> {
    fn write_scan(&mut self, scan: &Scan) -> anyhow::Result<()> {
        let frames = self.sensor.encode(scan)?;
        let mut bytes = Vec::with_capacity(frames.len() * 22);
        for f in &frames {
            slcan::write_frame(f, &mut bytes);
        }
        self.scans += 1;
        if self.corrupt_every > 0 && self.scans.is_multiple_of(self.corrupt_every) {
            let mid = bytes.len() / 2;
            if bytes[mid] != b'\r' {
                bytes[mid] = b'G';
            }
            bytes.splice(0..0, *b"garbage\r");
        }
        self.write_raw(&bytes)?;
        Ok(())
    }

    fn dropped(&self) -> u64 {
        self.dropped_bytes
    }
}

/// A candump log of a CAN range sensor's traffic. Frames of a scan are stamped
/// from the scan's stamp, `frame_spacing` apart (a 8-byte frame takes about
/// 111 µs at 1 Mbit/s).
pub struct CandumpWriter<W: Write> {
    pub out: W,
    pub sensor: CanSensorConfig,
    pub interface: String,
    pub frame_spacing: Duration,
}

impl<W: Write> CandumpWriter<W> {
    pub fn new(out: W, sensor: CanSensorConfig, interface: &str) -> Self {
        Self {
            out,
            sensor,
            interface: interface.to_owned(),
            frame_spacing: Duration::from_micros(250),
        }
    }

    /// Writes one log line.
    pub fn write_frame(&mut self, stamp_ns: u64, frame: &CanFrame) -> io::Result<()> {
        let record = CandumpRecord {
            stamp_ns,
            interface: self.interface.clone(),
            frame: *frame,
        };
        writeln!(self.out, "{}", format_candump_line(&record))
    }
}

impl<W: Write> ScanSink for CandumpWriter<W> {
    fn write_scan(&mut self, scan: &Scan) -> anyhow::Result<()> {
        let step = self.frame_spacing.as_nanos() as u64;
        for (i, frame) in self.sensor.encode(scan)?.iter().enumerate() {
            self.write_frame(scan.stamp_ns + i as u64 * step, frame)?;
        }
        self.out.flush()?;
        Ok(())
    }
}
