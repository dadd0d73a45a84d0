//! Measurements nodes report about themselves: latency percentiles and message
//! rates. Pure: callers pass the timestamps in.

mod percentiles;
mod rate;
mod summary;

pub use percentiles::{LatencySummary, Percentiles};
pub use rate::RateMeter;
pub use summary::GraphSummary;
