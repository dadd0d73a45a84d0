//! Recording and replaying a namespace's messages (MCAP files written and read
//! by `shroud record`, `shroud replay` and `shroud mcap info`): the decisions,
//! as plain data. Which topics a recording takes ([`TopicFilter`]), how shroud's
//! messages are laid out as MCAP schemas and channels ([`layout`]), when a chunk
//! or a file ends ([`ChunkPolicy`], [`SplitPolicy`]), what is dropped when the
//! disk is slow or full ([`ByteQueue`], [`DiskReserve`], [`DropCounts`]), and
//! when a replayed message is due ([`ReplaySchedule`]), how a recording's
//! bytes are read back, truncated or not ([`read_records`]), and how ROS 2
//! recordings (rosbag2) map to shroud's streams and back ([`ros2`]). Files and zenoh
//! live in `shroud-nodes`.

mod chunk;
mod drops;
mod error;
mod fields;
mod filter;
pub mod layout;
mod queue;
mod read;
mod rollover;
pub mod ros2;
mod schedule;

pub use drops::{DiskReserve, DropCause, DropCounts};
pub use error::RecordError;
pub use filter::TopicFilter;
pub use queue::ByteQueue;
pub use read::{read_records, Ending, ReadError};
pub use rollover::{split_path, ChunkPolicy, SplitPolicy};
pub use schedule::{Pace, ReplaySchedule};
