//! A device emulator behind a pseudo-terminal: the host opens the pty's slave
//! (or a stable link to it) like a real serial device; this loop carries bytes
//! between the master and the emulator, garbles them when the host's baud rate
//! is not the device's, and can stall or unplug the device on a schedule.

use super::pty::Pty;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use shroud_emulators::device::SerialDeviceEmulator;
use std::io::{self, Read, Write};
use std::os::fd::AsRawFd;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// How the emulated device is exposed and how it misbehaves in time.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct EmulatorLine {
    /// A symlink kept pointing at the current pty slave (a stable path across
    /// replugs, like `/dev/serial/by-id/...`).
    pub link: Option<PathBuf>,
    /// Seconds after start (and after each replug) until the device stops
    /// sending for `stall_for` seconds.
    pub stall_after: Option<f64>,
    pub stall_for: f64,
    /// Seconds after start until the device is unplugged (its pty closed) for
    /// `unplug_for` seconds; it comes back as a fresh device (powered up
    /// again) behind the same link.
    pub unplug_after: Option<f64>,
    pub unplug_for: f64,
    /// Stop after this many seconds (None: until stopped).
    pub duration: Option<f64>,
}

/// What the line carried.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct LineStats {
    pub bytes_to_host: u64,
    pub bytes_from_host: u64,
    /// Bytes lost: sent during a stall, or beyond the device's buffer while
    /// no host read them.
    pub bytes_dropped: u64,
    /// Bytes garbled because the host's baud rate was not the device's.
    pub bytes_garbled: u64,
    pub unplugs: u64,
}

/// Runs emulators made by `make` (one per power-up) on a pty until `stop`
/// is set or `line.duration` passes. `ready` is told the path a host should
/// open (the link if any, else the slave) each time the device (re)appears.
pub fn run_emulator(
    make: &mut dyn FnMut() -> anyhow::Result<Box<dyn SerialDeviceEmulator>>,
    line: &EmulatorLine,
    stop: &AtomicBool,
    ready: &mut dyn FnMut(&Path),
    on_stats: &mut dyn FnMut(&LineStats),
) -> io::Result<LineStats> {
    let start = Instant::now();
    let mut stats = LineStats::default();
    let mut unplug_at = line.unplug_after;
    loop {
        let pty = Pty::open()?;
        pty.set_nonblocking()?;
        let host_path = publish_path(&pty, line.link.as_deref())?;
        ready(&host_path);
        let mut device = make().map_err(io::Error::other)?;
        let plugged = Instant::now();
        let ended = carry(
            &mut Carry {
                pty,
                device: device.as_mut(),
                line,
                plugged,
                start,
                unplug_at,
                rng: Pcg64Mcg::seed_from_u64(0x5eed),
            },
            &mut stats,
            stop,
            on_stats,
        )?;
        match ended {
            CarryEnd::Unplugged => {
                stats.unplugs += 1;
                unplug_at = None;
                tracing::info!(
                    "emulated {} unplugged for {} s",
                    device.model(),
                    line.unplug_for
                );
                if let Some(link) = &line.link {
                    let _ = std::fs::remove_file(link);
                }
                if !super::sleep_unless_stopped(Duration::from_secs_f64(line.unplug_for), stop) {
                    break;
                }
            }
            CarryEnd::Done => break,
        }
    }
    remove_link(line);
    Ok(stats)
}

/// The path a host opens: the slave, or a link re-pointed at it.
fn publish_path(pty: &Pty, link: Option<&Path>) -> io::Result<PathBuf> {
    let Some(link) = link else {
        return Ok(pty.slave_path().to_owned());
    };
    let tmp = link.with_extension("new-link");
    let _ = std::fs::remove_file(&tmp);
    std::os::unix::fs::symlink(pty.slave_path(), &tmp)?;
    std::fs::rename(&tmp, link)?;
    Ok(link.to_owned())
}

enum CarryEnd {
    Unplugged,
    Done,
}

struct Carry<'a> {
    pty: Pty,
    device: &'a mut dyn SerialDeviceEmulator,
    line: &'a EmulatorLine,
    plugged: Instant,
    start: Instant,
    unplug_at: Option<f64>,
    rng: Pcg64Mcg,
}

/// The loop of one power-up: host bytes in, device bytes out, every 2 ms.
fn carry(
    c: &mut Carry<'_>,
    stats: &mut LineStats,
    stop: &AtomicBool,
    on_stats: &mut dyn FnMut(&LineStats),
) -> io::Result<CarryEnd> {
    let mut inbound = vec![0u8; 4096];
    let mut outbound = Vec::new();
    let mut unsent = Unsent::default();
    let mut host = false;
    let mut last_report = Instant::now();
    while !stop.load(Ordering::Relaxed) {
        let since_start = c.start.elapsed().as_secs_f64();
        if c.line.duration.is_some_and(|d| since_start >= d) {
            remove_link(c.line);
            return Ok(CarryEnd::Done);
        }
        if c.unplug_at.is_some_and(|t| since_start >= t) {
            // The name goes before the device: a host never opens a pty
            // about to close (or, later, a stranger's reusing its number).
            remove_link(c.line);
            return Ok(CarryEnd::Unplugged);
        }
        let now = c.plugged.elapsed().as_secs_f64();
        let host_baud = host_baud(&c.pty);
        let wrong_baud = matches!((c.device.uart_baud(), host_baud), (Some(d), Some(h)) if d != h);
        match c.pty.master().read(&mut inbound) {
            // EIO: no host holds the slave open (a crashed or unplugged
            // driver); the device goes on regardless.
            Err(e) if e.raw_os_error() == Some(libc::EIO) => host = false,
            Err(_) => host = true,
            Ok(0) => {}
            Ok(n) => {
                host = true;
                stats.bytes_from_host += n as u64;
                if wrong_baud {
                    // At the wrong rate a UART samples noise: the device
                    // understands nothing the host says.
                    stats.bytes_garbled += n as u64;
                } else {
                    c.device.receive(&inbound[..n], now);
                }
            }
        }
        outbound.clear();
        c.device.poll(now, &mut outbound);
        let stalled = c
            .line
            .stall_after
            .is_some_and(|t| now >= t && now < t + c.line.stall_for);
        if stalled {
            stats.bytes_dropped += outbound.len() as u64;
        } else {
            unsent.push(&outbound, host, stats);
        }
        if host {
            // Garbled as they go out: at the wrong rate a UART reads noise.
            let garble = wrong_baud.then_some(&mut c.rng);
            unsent.send(&mut c.pty, garble, stats);
        }
        if last_report.elapsed() >= Duration::from_millis(500) {
            last_report = Instant::now();
            on_stats(stats);
        }
        std::thread::sleep(Duration::from_millis(2));
    }
    remove_link(c.line);
    Ok(CarryEnd::Done)
}

fn remove_link(line: &EmulatorLine) {
    if let Some(link) = &line.link {
        let _ = std::fs::remove_file(link);
    }
}

/// What the device has sent that no host has read yet: a USB device's (or a
/// UART's) buffer, so that a host opening the port late, or again after a
/// crash, first reads what the device kept sending meanwhile. Bounded, the
/// oldest bytes going first (counted as dropped): to a device's few KB while
/// no host holds the port open, to [`HOST_BACKLOG`] while one does but reads
/// slower than the device sends.
#[derive(Default)]
struct Unsent {
    bytes: std::collections::VecDeque<u8>,
}

/// How much a device (or a USB-serial adapter) holds for a host that does
/// not read: a few KB, about two URG scans.
const DEVICE_BUFFER: usize = 4 << 10;

/// How far a reading host may fall behind (the pty's own buffer is full):
/// many of the largest scans (a UTM-30LX multi-echo scan with intensity is
/// under 30 KB), never unbounded.
const HOST_BACKLOG: usize = 1 << 20;

impl Unsent {
    fn push(&mut self, bytes: &[u8], host: bool, stats: &mut LineStats) {
        self.bytes.extend(bytes);
        let bound = if host { HOST_BACKLOG } else { DEVICE_BUFFER };
        let excess = self.bytes.len().saturating_sub(bound);
        self.bytes.drain(..excess);
        stats.bytes_dropped += excess as u64;
    }

    /// Writes what the pty takes now (as noise, with `garble`); the rest waits.
    fn send(&mut self, pty: &mut Pty, mut garble: Option<&mut Pcg64Mcg>, stats: &mut LineStats) {
        while !self.bytes.is_empty() {
            let (front, _) = self.bytes.as_slices();
            let mut noise;
            let mut out = front;
            if let Some(rng) = garble.as_deref_mut() {
                noise = front.to_vec();
                noise.iter_mut().for_each(|b| *b = rng.random());
                out = &noise;
            }
            match pty.master().write(out) {
                Ok(0) => break,
                Ok(n) => {
                    stats.bytes_to_host += n as u64;
                    if garble.is_some() {
                        stats.bytes_garbled += n as u64;
                    }
                    self.bytes.drain(..n);
                }
                Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
                Err(_) => break,
            }
        }
    }
}

/// The baud rate the host set on the slave. Linux keeps one termios per pty
/// pair, read through the master (`tty_mode_ioctl` uses the linked tty).
fn host_baud(pty: &Pty) -> Option<u32> {
    let fd = pty.master_ref().as_raw_fd();
    // SAFETY: termios2 is plain data that TCGETS2 fills completely.
    let mut t: libc::termios2 = unsafe { std::mem::zeroed() };
    // SAFETY: a valid descriptor and a pointer to a termios2.
    if unsafe { libc::ioctl(fd, libc::TCGETS2, &mut t) } != 0 {
        return None;
    }
    Some(t.c_ospeed)
}
