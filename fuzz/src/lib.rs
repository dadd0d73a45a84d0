//! Coverage-guided fuzz targets for every decoder of outside bytes (files,
//! wire messages, configuration, device streams, the dashboard's frames), as a
//! library: `cargo fuzz` binaries (fuzz_targets/target.rs) and the corpus
//! replay test (tests/corpus.rs) run the same functions. Each target checks
//! more than "no panic": round trips, independence of chunking, errors that
//! name the problem, and a bound on the memory a decode allocates.

mod arm;
mod can_device;
mod can_records;
pub mod check;
mod round_trip;
mod seeds;
mod serial_device;
pub mod targets;

pub use targets::{Target, TARGETS};

/// The target called `name`.
pub fn target(name: &str) -> Option<&'static Target> {
    TARGETS.iter().find(|t| t.name == name)
}

/// Runs the target called `name` on one input, checking the memory it
/// allocates (when a counting allocator is installed). Panics on an unknown
/// name: a binary without a registered target is a build mistake.
pub fn fuzz(name: &str, data: &[u8]) {
    let target = target(name).unwrap_or_else(|| panic!("no fuzz target named {name:?}"));
    check::bounded_allocation(data.len(), || (target.run)(data));
}

/// The body of a fuzzer binary (`fuzz_targets/<name>.rs`): counts heap bytes
/// and fuzzes the target named like the binary.
#[cfg(feature = "libfuzzer")]
#[macro_export]
macro_rules! fuzz_binary {
    () => {
        /// Counts heap bytes so that each input's allocations are checked
        /// against its size ([`shroud_fuzz::check::bounded_allocation`]).
        #[global_allocator]
        static ALLOCATOR: shroud_graph::metrics::CountingAllocator =
            shroud_graph::metrics::CountingAllocator;

        libfuzzer_sys::fuzz_target!(|data: &[u8]| $crate::fuzz(env!("CARGO_BIN_NAME"), data));
    };
}

#[cfg(feature = "libfuzzer")]
pub use libfuzzer_sys;
