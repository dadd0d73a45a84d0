//! Proptest configuration: a fixed seed and case count by default (a
//! reproducible suite), both overridable through `PROPTEST_RNG_SEED` and
//! `PROPTEST_CASES` to explore further.

use proptest::test_runner::{Config, FileFailurePersistence, RngSeed};

/// Seed used when `PROPTEST_RNG_SEED` is not set.
const DEFAULT_SEED: u64 = 0x5348_524F_5544;

/// `cases` successful cases from a fixed seed, unless the environment says otherwise.
pub fn config(cases: u32) -> Config {
    let from_env = Config::default();
    Config {
        cases: if std::env::var_os("PROPTEST_CASES").is_some() {
            from_env.cases
        } else {
            cases
        },
        rng_seed: if std::env::var_os("PROPTEST_RNG_SEED").is_some() {
            from_env.rng_seed
        } else {
            RngSeed::Fixed(DEFAULT_SEED)
        },
        // Next to the test file (the default looks for a lib.rs that tests/ lacks).
        failure_persistence: Some(Box::new(FileFailurePersistence::WithSource(
            "proptest-regressions",
        ))),
        ..from_env
    }
}
