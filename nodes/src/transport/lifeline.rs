//! A child process's life tied to its parent's, and standard outputs that
//! outlive their reader. A launcher killed outright must leave no live node: the
//! parent-death signal alone is not enough (it comes from whichever launcher
//! thread forked, and may land when the node can no longer act on it), so a
//! node also watches its parent's pid itself.

use std::os::unix::process::CommandExt;
use std::time::Duration;

/// Set by [`die_with_parent`] to the spawning process's pid, read by
/// [`watch_parent`] in the child.
pub const PARENT_PID_ENV: &str = "SHROUD_LAUNCHER_PID";

/// How often a child checks that its parent is still there.
const PARENT_POLL: Duration = Duration::from_millis(150);

/// Makes the child of `cmd` stop with this process: SIGTERM when the forking
/// thread exits (`PR_SET_PDEATHSIG`), and this pid in [`PARENT_PID_ENV`] for the
/// child's [`watch_parent`].
pub fn die_with_parent(cmd: &mut std::process::Command) {
    let parent = std::process::id() as libc::pid_t;
    cmd.env(PARENT_PID_ENV, parent.to_string());
    // SAFETY: only async-signal-safe calls (prctl, getppid) run between fork
    // and exec, and the error is built from a plain code (no allocation).
    unsafe {
        cmd.pre_exec(move || {
            if libc::prctl(libc::PR_SET_PDEATHSIG, libc::SIGTERM) != 0 {
                return Err(std::io::Error::last_os_error());
            }
            // The parent may have died before prctl took effect: fail the
            // spawn (a signal would only reach the parent's inherited
            // handlers here, before exec).
            if libc::getppid() != parent {
                return Err(std::io::Error::from_raw_os_error(libc::ESRCH));
            }
            Ok(())
        });
    }
}

/// If this process was started by [`die_with_parent`], calls `on_gone` once
/// (from a watcher thread) when that parent is gone. A dying process's children
/// are reparented as it exits, whether or not anyone ever reaps it, so
/// getppid() changes at the parent's death. Returns whether it watches.
pub fn watch_parent(on_gone: impl FnOnce() + Send + 'static) -> bool {
    let Some(parent) = std::env::var(PARENT_PID_ENV)
        .ok()
        .and_then(|v| v.parse::<libc::pid_t>().ok())
    else {
        return false;
    };
    let watcher = move || {
        // SAFETY: getppid(2) cannot fail.
        while unsafe { libc::getppid() } == parent {
            std::thread::sleep(PARENT_POLL);
        }
        // The parent held our output pipes: make sure the stop's log lines
        // cannot fail before acting on it.
        silence_broken_outputs();
        on_gone();
    };
    std::thread::Builder::new()
        .name("parent-watch".into())
        .spawn(watcher)
        .is_ok()
}

/// Keeps stdout and stderr writable after their reader is gone (a killed
/// launcher, `| head`): a thread blocks in poll(2) until one reports it (POLLERR
/// on a pipe without reader, POLLHUP on a hung-up terminal), then points it at
/// /dev/null. Without this the first log line after that panics the thread that
/// logs: tracing-subscriber reports the failed write with `eprintln!`, which
/// panics on EPIPE.
pub fn keep_outputs_writable() {
    static STARTED: std::sync::Once = std::sync::Once::new();
    STARTED.call_once(|| {
        let watcher = || {
            let mut fds = outputs();
            while redirect_broken(&mut fds, -1) {}
        };
        let _ = std::thread::Builder::new()
            .name("output-watch".into())
            .spawn(watcher);
    });
}

/// Points a broken stdout or stderr at /dev/null now, without waiting: for the
/// moment before a line that must not fail (the watcher may not have woken yet).
pub fn silence_broken_outputs() {
    redirect_broken(&mut outputs(), 0);
}

/// Writes a process's last line to stderr and exits with `code`, whatever
/// else is stuck: the line goes out with one raw write(2) (no lock that a
/// thread blocked on a full pipe could hold), skipped if stderr cannot take
/// it, and `_exit` runs no destructor or atexit handler that could hang.
pub fn last_words_and_exit(line: &str, code: libc::c_int) -> ! {
    silence_broken_outputs();
    let mut p = libc::pollfd {
        fd: 2,
        events: libc::POLLOUT,
        revents: 0,
    };
    // SAFETY: poll/alarm/write on stderr with a valid buffer, then _exit.
    unsafe {
        if libc::poll(&mut p, 1, 100) == 1 && p.revents & libc::POLLOUT != 0 {
            // A stopped terminal can block even after POLLOUT: SIGALRM's
            // default action ends the process then.
            libc::alarm(1);
            libc::write(2, line.as_ptr().cast(), line.len());
        }
        libc::_exit(code)
    }
}

fn outputs() -> [libc::pollfd; 2] {
    [1, 2].map(|fd| libc::pollfd {
        fd,
        events: 0,
        revents: 0,
    })
}

/// Waits up to `timeout_ms` (-1: forever) for one of `fds` to break, and points
/// the broken ones at /dev/null (which never reports again, so a watcher simply
/// blocks from then on). A closed descriptor is dropped from `fds`: poll(2)
/// would report it at once, every time. Returns whether any is left to watch.
fn redirect_broken(fds: &mut [libc::pollfd], timeout_ms: libc::c_int) -> bool {
    // SAFETY: a valid array of pollfd and its length.
    let n = unsafe { libc::poll(fds.as_mut_ptr(), fds.len() as libc::nfds_t, timeout_ms) };
    if n < 0 && std::io::Error::last_os_error().kind() != std::io::ErrorKind::Interrupted {
        return false;
    }
    for p in fds.iter_mut().filter(|p| n > 0 && p.revents != 0) {
        if p.revents & libc::POLLNVAL != 0 {
            p.fd = -1;
        } else if p.revents & (libc::POLLERR | libc::POLLHUP) != 0 && !to_dev_null(p.fd) {
            // Still broken (no descriptor to spare): stop watching it rather
            // than spin on it.
            p.fd = -1;
        }
    }
    fds.iter().any(|p| p.fd >= 0)
}

/// Points `fd` at /dev/null; whether that worked.
fn to_dev_null(fd: libc::c_int) -> bool {
    // SAFETY: open/dup2/close on a path literal and descriptors we own; dup2
    // swaps the descriptor atomically under concurrent writers.
    unsafe {
        let null = libc::open(c"/dev/null".as_ptr(), libc::O_WRONLY | libc::O_CLOEXEC);
        if null < 0 {
            return false;
        }
        let swapped = libc::dup2(null, fd) >= 0;
        libc::close(null);
        swapped
    }
}
