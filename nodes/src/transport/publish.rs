//! Payloads for publishing: large messages go through zenoh shared memory when a
//! provider could be created (receivers on the same machine then map the buffer
//! instead of receiving a copy over TCP); anything else takes the copy path.

use shroud_msg::{encode_into, encoded_len, MessageError};
use std::num::NonZeroUsize;
use std::sync::atomic::{AtomicU64, Ordering};
use zenoh::bytes::ZBytes;
use zenoh::shm::{
    AllocAlignment, GarbageCollect, PosixShmProviderBackend, ShmProvider, ShmProviderBuilder,
    ZShmMut,
};
use zenoh::Wait;

/// Below this size a copy is cheaper than an allocation in the shared segment.
const SHM_THRESHOLD: usize = 64 * 1024;

pub struct PayloadWriter {
    provider: Option<ShmProvider<PosixShmProviderBackend>>,
    shm_sent: AtomicU64,
    copy_sent: AtomicU64,
}

impl PayloadWriter {
    /// `pool_bytes` is the shared segment's size (a few messages' worth);
    /// `enabled = false` or a failure to create the segment selects the copy path.
    pub fn new(enabled: bool, pool_bytes: usize) -> Self {
        let provider = if enabled && pool_bytes >= SHM_THRESHOLD {
            // Every buffer 4-byte aligned (see `alloc`).
            let layout = (
                NonZeroUsize::new(pool_bytes.next_multiple_of(4)).unwrap_or(NonZeroUsize::MIN),
                AllocAlignment::ALIGN_4_BYTES,
            );
            match ShmProviderBuilder::default_backend(layout).wait() {
                Ok(p) => Some(p),
                Err(e) => {
                    tracing::warn!("shared memory unavailable, publishing by copy: {e}");
                    None
                }
            }
        } else {
            None
        };
        Self {
            provider,
            shm_sent: AtomicU64::new(0),
            copy_sent: AtomicU64::new(0),
        }
    }

    pub fn uses_shm(&self) -> bool {
        self.provider.is_some()
    }

    /// `message` encoded straight into a shared buffer when it is large and
    /// shared memory is available (one pass over the points, no intermediate
    /// vector); otherwise encoded into a vector.
    pub fn encode<T: serde::Serialize>(&self, message: &T) -> Result<ZBytes, MessageError> {
        let len = encoded_len(message)?;
        if len >= SHM_THRESHOLD {
            if let Some(mut buf) = self.alloc(len) {
                encode_into(message, &mut buf)?;
                self.shm_sent.fetch_add(1, Ordering::Relaxed);
                return Ok(ZBytes::from(buf));
            }
        }
        let mut bytes = vec![0; len];
        encode_into(message, &mut bytes)?;
        self.copy_sent.fetch_add(1, Ordering::Relaxed);
        Ok(ZBytes::from(bytes))
    }

    /// `bytes` (an encoded message, e.g. replayed from a recording) as a
    /// payload: copied into a shared buffer when large and shared memory is
    /// available, else into a vector.
    pub fn copy(&self, bytes: &[u8]) -> ZBytes {
        if bytes.len() >= SHM_THRESHOLD {
            if let Some(mut buf) = self.alloc(bytes.len()) {
                buf.copy_from_slice(bytes);
                self.shm_sent.fetch_add(1, Ordering::Relaxed);
                return ZBytes::from(buf);
            }
        }
        self.copy_sent.fetch_add(1, Ordering::Relaxed);
        ZBytes::from(bytes.to_vec())
    }

    /// A shared buffer of `len` bytes, or `None` without shared memory, when the
    /// segment is full (receivers still holding old buffers: the caller then
    /// copies rather than block), or when `len` is not a multiple of 4.
    ///
    /// Buffers are 4-byte aligned so that an aligned cloud's floats can be read
    /// in place; the allocator rounds sizes up to the alignment, and a payload
    /// must not carry trailing bytes (strict MessagePack decoders refuse them).
    fn alloc(&self, len: usize) -> Option<ZShmMut> {
        let provider = self.provider.as_ref()?;
        if !len.is_multiple_of(4) {
            return None;
        }
        let layout = (NonZeroUsize::new(len)?, AllocAlignment::ALIGN_4_BYTES);
        provider
            .alloc(layout)
            .with_policy::<GarbageCollect>()
            .wait()
            .ok()
    }

    /// (sent through shared memory, sent by copy).
    pub fn counts(&self) -> (u64, u64) {
        (
            self.shm_sent.load(Ordering::Relaxed),
            self.copy_sent.load(Ordering::Relaxed),
        )
    }
}
