//! zenoh transport: session configuration from the command line, the one
//! blocking queue between a subscriber and its worker, and publishing
//! through shared memory when it is available, and removing zenoh's
//! shared-memory segments at exit; child processes tied to their parent's life.

mod args;
mod clock;
mod host;
mod lifeline;
mod publish;
mod qos;
mod shm_cleanup;
mod signal;
mod wait_queue;
mod zenoh_drops;

pub use args::{OnOff, ZenohArgs};
pub use clock::{monotonic_ns, sample_published_ns, unix_ns};
pub use lifeline::{
    die_with_parent, keep_outputs_writable, last_words_and_exit, silence_broken_outputs,
    watch_parent,
};
pub use publish::PayloadWriter;
pub use qos::topic_publisher;
pub use shm_cleanup::{is_zenoh_segment, release_shm_segments};
pub use signal::shutdown_signal;
pub use wait_queue::{Backlog, WaitQueue};
pub use zenoh_drops::session_drops;
