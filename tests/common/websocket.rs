//! A WebSocket client at the byte level, for the dashboard's fault tests: the
//! opening handshake (RFC 6455 section 4.1) over a plain TCP stream, then
//! either a reader that takes and discards whatever comes (a browser that
//! keeps up), or nothing at all (a browser that stopped reading: the stream is
//! never read again, and its receive buffer can be made small so that the
//! server feels it at once).

use std::io::{Read, Write};
use std::net::{Shutdown, TcpStream};
use std::os::fd::AsRawFd;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

pub struct RawWebSocket {
    pub stream: TcpStream,
}

impl RawWebSocket {
    /// Connects to `ws://address/ws`, with a receive buffer of
    /// `receive_buffer` bytes if given (the kernel's own sizing otherwise).
    pub fn connect(address: &str, receive_buffer: Option<usize>) -> RawWebSocket {
        let mut stream = TcpStream::connect(address).expect("the dashboard listens");
        if let Some(bytes) = receive_buffer {
            set_receive_buffer(&stream, bytes);
        }
        // The RFC's sample nonce: the server's answer is not checked beyond 101.
        write!(
            stream,
            "GET /ws HTTP/1.1\r\nHost: {address}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n\
             Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n"
        )
        .expect("the handshake is sent");
        let head = read_head(&mut stream);
        assert!(
            head.starts_with("HTTP/1.1 101"),
            "the dashboard upgrades the connection: {head}"
        );
        RawWebSocket { stream }
    }

    /// Reads and discards everything from now on (a thread); counts the bytes.
    pub fn keep_reading(self) -> WebSocketReader {
        let bytes = Arc::new(AtomicU64::new(0));
        let (count, mut stream) = (bytes.clone(), self.stream.try_clone().unwrap());
        let thread = std::thread::spawn(move || {
            let mut buf = vec![0u8; 64 * 1024];
            while let Ok(n @ 1..) = stream.read(&mut buf) {
                count.fetch_add(n as u64, Ordering::Relaxed);
            }
        });
        WebSocketReader {
            bytes,
            stream: self.stream,
            thread: Some(thread),
        }
    }
}

/// The response head, read byte by byte so that no frame byte is taken.
fn read_head(stream: &mut TcpStream) -> String {
    let mut head = Vec::new();
    let mut byte = [0u8; 1];
    while !head.ends_with(b"\r\n\r\n") {
        match stream.read(&mut byte) {
            Ok(1) => head.push(byte[0]),
            _ => panic!(
                "the connection closed during the handshake: {}",
                String::from_utf8_lossy(&head)
            ),
        }
        assert!(head.len() < 8192, "an endless response head");
    }
    String::from_utf8_lossy(&head).into_owned()
}

fn set_receive_buffer(stream: &TcpStream, bytes: usize) {
    let size = bytes as libc::c_int;
    // SAFETY: setsockopt on an open socket with a valid int option value.
    let done = unsafe {
        libc::setsockopt(
            stream.as_raw_fd(),
            libc::SOL_SOCKET,
            libc::SO_RCVBUF,
            (&size as *const libc::c_int).cast(),
            std::mem::size_of::<libc::c_int>() as libc::socklen_t,
        )
    };
    assert_eq!(done, 0, "SO_RCVBUF: {}", std::io::Error::last_os_error());
}

/// A client that keeps reading until dropped.
pub struct WebSocketReader {
    bytes: Arc<AtomicU64>,
    stream: TcpStream,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl WebSocketReader {
    /// Bytes received so far (after the handshake).
    pub fn bytes(&self) -> u64 {
        self.bytes.load(Ordering::Relaxed)
    }
}

impl Drop for WebSocketReader {
    fn drop(&mut self) {
        let _ = self.stream.shutdown(Shutdown::Both);
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}
