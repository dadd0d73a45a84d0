//! Payloads for publishing: large messages go through zenoh shared memory when a
//! provider could be created (receivers on the same machine then map the buffer
//! instead of receiving a copy over TCP); anything else takes the copy path.

use std::sync::atomic::{AtomicU64, Ordering};
use zenoh::bytes::ZBytes;
use zenoh::shm::{GarbageCollect, PosixShmProviderBackend, ShmProvider, ShmProviderBuilder};
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
            match ShmProviderBuilder::default_backend(pool_bytes).wait() {
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

    /// A payload holding `bytes`: in shared memory when possible. A full segment
    /// (receivers still holding old buffers) falls back to a copy rather than block.
    pub fn payload(&self, bytes: Vec<u8>) -> ZBytes {
        if bytes.len() >= SHM_THRESHOLD {
            if let Some(provider) = &self.provider {
                if let Ok(mut buf) = provider
                    .alloc(bytes.len())
                    .with_policy::<GarbageCollect>()
                    .wait()
                {
                    buf.copy_from_slice(&bytes);
                    self.shm_sent.fetch_add(1, Ordering::Relaxed);
                    return ZBytes::from(buf);
                }
            }
        }
        self.copy_sent.fetch_add(1, Ordering::Relaxed);
        ZBytes::from(bytes)
    }

    /// (sent through shared memory, sent by copy).
    pub fn counts(&self) -> (u64, u64) {
        (
            self.shm_sent.load(Ordering::Relaxed),
            self.copy_sent.load(Ordering::Relaxed),
        )
    }
}
