//! An entity's gid as rmw_zenoh derives it: XXH3-128 of its liveliness
//! token's key expression, low 64 bits then high 64 bits, each in the
//! machine's (little-endian) order (liveliness_utils.cpp@3411fdec, `Entity::Entity`).

use xxhash_rust::xxh3::xxh3_128;

/// The gid rmw_zenoh gives the entity whose token is `token_keyexpr`.
pub fn entity_gid(token_keyexpr: &str) -> [u8; 16] {
    // u128 little endian = low64 LE then high64 LE, as memcpy on x86/ARM.
    xxh3_128(token_keyexpr.as_bytes()).to_le_bytes()
}
