//! A link with delay and loss between a host's namespace and the LAN's
//! bridge, for the multi-host tests. This machine's kernel has no `netem`
//! qdisc (nor `gact`, nor iptables), so the host's end of the link and the
//! bridge's end are TAP devices, and a thread of the test process copies
//! Ethernet frames between them: it holds each frame for the one-way delay
//! and drops each with the loss probability (a seeded generator, so a run
//! can be repeated). TCP then sees what it would on a real lossy, long link:
//! retransmissions and a longer round trip. Bandwidth is limited by the
//! kernel (`tbf` on the TAPs, [`super::netns::Lan::limit_rate`]), before the
//! delay, as a slow link's serialisation comes before its propagation.

use rand::{Rng, SeedableRng};
use std::collections::VecDeque;
use std::fs::{File, OpenOptions};
use std::os::fd::{AsRawFd, OwnedFd};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// What the link does to each frame, the same in both directions.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Impairment {
    /// One-way delay.
    pub delay: Duration,
    /// Probability that a frame is dropped, 0 to 1.
    pub loss: f64,
}

/// Frames the relay handled, both directions together.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RelayCounts {
    /// Written to the other TAP.
    pub forwarded: u64,
    /// Dropped by the loss probability.
    pub lost: u64,
    /// Dropped because the relay already held [`HELD_MAX`] frames, or the
    /// other TAP would not take them (a write error or a short write).
    pub refused: u64,
}

/// The relay thread between two TAPs; stopped when dropped.
pub struct Relay {
    impairment: Arc<Mutex<Impairment>>,
    counts: Arc<Mutex<RelayCounts>>,
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
}

/// A TAP named `name` (made beforehand with `ip tuntap add ... mode tap`)
/// in network namespace `ns`, opened non-blocking, frames without a packet
/// information header. Moves the calling thread into `ns` (a network
/// namespace is per thread).
fn open_tap(ns: &str, name: &str) -> std::io::Result<OwnedFd> {
    let namespace = File::open(format!("/run/netns/{ns}"))?;
    if unsafe { libc::setns(namespace.as_raw_fd(), libc::CLONE_NEWNET) } != 0 {
        return Err(std::io::Error::last_os_error());
    }
    let tun = OpenOptions::new()
        .read(true)
        .write(true)
        .open("/dev/net/tun")?;
    // struct ifreq: the name (16 bytes), then the flags (a short).
    let mut request = [0u8; 40];
    request[..name.len()].copy_from_slice(name.as_bytes());
    let flags = (libc::IFF_TAP | libc::IFF_NO_PI) as i16;
    request[16..18].copy_from_slice(&flags.to_ne_bytes());
    let fd = tun.as_raw_fd();
    if unsafe { libc::ioctl(fd, libc::TUNSETIFF, request.as_mut_ptr()) } != 0 {
        return Err(std::io::Error::last_os_error());
    }
    if unsafe { libc::fcntl(fd, libc::F_SETFL, libc::O_NONBLOCK) } != 0 {
        return Err(std::io::Error::last_os_error());
    }
    Ok(tun.into())
}

/// Frames on their way in one direction, due in order (one delay for all).
struct Direction {
    from: OwnedFd,
    to: OwnedFd,
    due: VecDeque<(Instant, Vec<u8>)>,
}

/// Frames held at most, per direction: 1 Gbit/s for 1.5 s of delay.
pub const HELD_MAX: usize = 125_000;

/// Frames read from one direction per wake-up, so that the other direction
/// and the frames that are due are not kept waiting.
const TAKEN_MAX: usize = 64;

impl Direction {
    /// Reads what `from` has (at most [`TAKEN_MAX`] frames), dropping or
    /// queueing each frame.
    fn take(
        &mut self,
        link: Impairment,
        random: &mut rand_pcg::Pcg64,
        counts: &mut RelayCounts,
        frame: &mut [u8],
    ) {
        for _ in 0..TAKEN_MAX {
            let n = unsafe {
                libc::read(
                    self.from.as_raw_fd(),
                    frame.as_mut_ptr().cast(),
                    frame.len(),
                )
            };
            if n <= 0 {
                return;
            }
            if random.random::<f64>() < link.loss {
                counts.lost += 1;
            } else if self.due.len() >= HELD_MAX {
                counts.refused += 1;
            } else {
                let due = Instant::now() + link.delay;
                self.due.push_back((due, frame[..n as usize].to_vec()));
            }
        }
    }

    /// Writes the frames that are due; when the next one is due.
    fn release(&mut self, now: Instant, counts: &mut RelayCounts) -> Option<Instant> {
        while let Some((due, frame)) = self.due.front() {
            if *due > now {
                return Some(*due);
            }
            let fd = self.to.as_raw_fd();
            let n = unsafe { libc::write(fd, frame.as_ptr().cast(), frame.len()) };
            match n == frame.len() as isize {
                true => counts.forwarded += 1,
                false => counts.refused += 1,
            }
            self.due.pop_front();
        }
        None
    }
}

impl Relay {
    /// Relays between TAP `host_tap` in namespace `host_ns` and TAP
    /// `bridge_tap` in `bridge_ns`, passing every frame until
    /// [`Relay::set`] says otherwise. Both TAPs are open when this returns.
    pub fn start(
        host_ns: &str,
        host_tap: &str,
        bridge_ns: &str,
        bridge_tap: &str,
    ) -> std::io::Result<Relay> {
        let impairment = Arc::new(Mutex::new(Impairment::default()));
        let counts = Arc::new(Mutex::new(RelayCounts::default()));
        let stop = Arc::new(AtomicBool::new(false));
        let (opened_tx, opened) = std::sync::mpsc::channel();
        let names = [host_ns, host_tap, bridge_ns, bridge_tap].map(str::to_string);
        let (link, tally, stopped) = (impairment.clone(), counts.clone(), stop.clone());
        let thread = std::thread::spawn(move || {
            let [host_ns, host_tap, bridge_ns, bridge_tap] = names;
            let taps = open_tap(&host_ns, &host_tap)
                .and_then(|host| Ok((host, open_tap(&bridge_ns, &bridge_tap)?)));
            let (host, bridge) = match taps {
                Ok(taps) => taps,
                Err(e) => return drop(opened_tx.send(Err(e))),
            };
            let (Ok(host2), Ok(bridge2)) = (host.try_clone(), bridge.try_clone()) else {
                return drop(opened_tx.send(Err(std::io::Error::other("dup"))));
            };
            let _ = opened_tx.send(Ok(()));
            let mut directions = [
                Direction {
                    from: host,
                    to: bridge2,
                    due: VecDeque::new(),
                },
                Direction {
                    from: bridge,
                    to: host2,
                    due: VecDeque::new(),
                },
            ];
            relay(&mut directions, &link, &tally, &stopped);
        });
        opened
            .recv()
            .map_err(|_| std::io::Error::other("the relay thread ended"))??;
        Ok(Relay {
            impairment,
            counts,
            stop,
            thread: Some(thread),
        })
    }

    /// What the link does from now on (frames already held keep their due
    /// time, and a frame taken later leaves after them: a shorter delay
    /// takes effect once they are gone).
    pub fn set(&self, impairment: Impairment) {
        *self.impairment.lock().unwrap() = impairment;
    }

    /// What the relay did so far.
    pub fn counts(&self) -> RelayCounts {
        *self.counts.lock().unwrap()
    }
}

/// The relay's loop: release due frames, wait for a frame or the next due
/// time (at most 20 ms, to see `stop`), take what came.
fn relay(
    directions: &mut [Direction; 2],
    link: &Mutex<Impairment>,
    tally: &Mutex<RelayCounts>,
    stop: &AtomicBool,
) {
    let mut random = rand_pcg::Pcg64::seed_from_u64(26);
    let mut frame = vec![0u8; 65_536];
    while !stop.load(Ordering::Relaxed) {
        let now = Instant::now();
        let mut counts = *tally.lock().unwrap();
        let next = directions
            .iter_mut()
            .filter_map(|d| d.release(now, &mut counts))
            .min();
        let wait = next.map_or(Duration::from_millis(20), |due| due - now);
        let wait = wait.min(Duration::from_millis(20));
        let mut polled = directions.each_ref().map(|d| libc::pollfd {
            fd: d.from.as_raw_fd(),
            events: libc::POLLIN,
            revents: 0,
        });
        let timeout = libc::timespec {
            tv_sec: 0,
            tv_nsec: wait.as_nanos() as libc::c_long,
        };
        unsafe { libc::ppoll(polled.as_mut_ptr(), 2, &timeout, std::ptr::null()) };
        let impairment = *link.lock().unwrap();
        for (d, p) in directions.iter_mut().zip(&polled) {
            if p.revents & libc::POLLIN != 0 {
                d.take(impairment, &mut random, &mut counts, &mut frame);
            }
        }
        *tally.lock().unwrap() = counts;
    }
}

impl Drop for Relay {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}
