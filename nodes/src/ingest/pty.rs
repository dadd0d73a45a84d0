//! Pseudo-terminals for simulated serial devices: a master the simulator
//! writes, a slave path a reader opens like any serial port.

use std::ffi::CStr;
use std::fs::File;
use std::io;
use std::os::fd::{FromRawFd, OwnedFd};
use std::path::{Path, PathBuf};

/// A pseudo-terminal pair in raw mode. The slave side is closed after setup:
/// readers open it by path (as often as they like while the master lives), and
/// dropping the master is the device being unplugged.
#[derive(Debug)]
pub struct Pty {
    master: File,
    slave_path: PathBuf,
}

impl Pty {
    /// Opens a pair, sets the slave to raw mode (no echo, no line editing, no
    /// CR/LF translation) and closes it.
    pub fn open() -> io::Result<Self> {
        let (mut master, mut slave) = (-1, -1);
        // SAFETY: openpty writes two descriptors; name, termios and winsize may be null.
        let rc = unsafe {
            libc::openpty(
                &mut master,
                &mut slave,
                std::ptr::null_mut(),
                std::ptr::null(),
                std::ptr::null(),
            )
        };
        if rc != 0 {
            return Err(io::Error::last_os_error());
        }
        // SAFETY: both descriptors were just returned open by openpty and are owned here.
        let (master, slave) = unsafe { (File::from_raw_fd(master), OwnedFd::from_raw_fd(slave)) };
        let slave_path = tty_name(&slave)?;
        make_raw(&slave)?;
        drop(slave);
        Ok(Self { master, slave_path })
    }

    /// The path a reader opens (`/dev/pts/N`).
    pub fn slave_path(&self) -> &Path {
        &self.slave_path
    }

    /// The master side: bytes written here arrive at the slave.
    pub fn master(&mut self) -> &mut File {
        &mut self.master
    }

    /// The master side, for ioctls.
    pub fn master_ref(&self) -> &File {
        &self.master
    }

    /// Makes reads and writes of the master return `WouldBlock` instead of
    /// blocking (nothing to read, or nobody drains the slave).
    pub fn set_nonblocking(&self) -> io::Result<()> {
        use std::os::fd::AsRawFd;
        let fd = self.master.as_raw_fd();
        // SAFETY: fcntl on a descriptor we own.
        let flags = unsafe { libc::fcntl(fd, libc::F_GETFL) };
        if flags < 0 || unsafe { libc::fcntl(fd, libc::F_SETFL, flags | libc::O_NONBLOCK) } < 0 {
            return Err(io::Error::last_os_error());
        }
        Ok(())
    }

    /// Another handle on the master (the pair lives until every handle is dropped).
    pub fn master_clone(&self) -> io::Result<File> {
        self.master.try_clone()
    }

    pub fn into_master(self) -> File {
        self.master
    }
}

fn tty_name(fd: &OwnedFd) -> io::Result<PathBuf> {
    use std::os::fd::AsRawFd;
    use std::os::unix::ffi::OsStrExt;
    let mut buf = [0 as libc::c_char; 256];
    // SAFETY: ttyname_r writes a NUL-terminated name of at most buf.len() bytes.
    let rc = unsafe { libc::ttyname_r(fd.as_raw_fd(), buf.as_mut_ptr(), buf.len()) };
    if rc != 0 {
        return Err(io::Error::from_raw_os_error(rc));
    }
    // SAFETY: on success buf holds a NUL-terminated string.
    let name = unsafe { CStr::from_ptr(buf.as_ptr()) };
    Ok(PathBuf::from(std::ffi::OsStr::from_bytes(name.to_bytes())))
}

fn make_raw(fd: &OwnedFd) -> io::Result<()> {
    use std::os::fd::AsRawFd;
    // SAFETY: termios is plain data; tcgetattr fills it before use.
    let mut termios: libc::termios = unsafe { std::mem::zeroed() };
    if unsafe { libc::tcgetattr(fd.as_raw_fd(), &mut termios) } != 0 {
        return Err(io::Error::last_os_error());
    }
    // SAFETY: cfmakeraw edits the struct in place.
    unsafe { libc::cfmakeraw(&mut termios) };
    if unsafe { libc::tcsetattr(fd.as_raw_fd(), libc::TCSANOW, &termios) } != 0 {
        return Err(io::Error::last_os_error());
    }
    Ok(())
}
