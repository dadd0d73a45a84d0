//! Measurements nodes report about themselves: latency percentiles and message
//! rates (pure: callers pass the timestamps in), what zenoh dropped, and the heap a computation
//! takes, through a counting allocator that benchmarks install.

mod allocation;
pub mod names;
mod node_health;
mod percentiles;
mod rate;
mod sequence_gaps;
mod summary;
mod zenoh_drops;

pub use allocation::{is_counting, live_bytes, peak_bytes, reset_peak, CountingAllocator};
pub use node_health::{NodeHealth, NodeRow, NodeState};
pub use percentiles::{LatencySummary, Percentiles};
pub use rate::RateMeter;
pub use sequence_gaps::SequenceGaps;
pub use summary::GraphSummary;
pub use zenoh_drops::ZenohDrops;
