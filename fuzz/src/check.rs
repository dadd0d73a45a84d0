//! The properties targets check besides "no panic": outputs independent of
//! how a stream is chunked, errors whose text names the problem, and heap use
//! bounded by the input's size.

use shroud_graph::metrics;
use std::fmt::{Debug, Display};

/// Heap a decode may allocate beyond [`ALLOCATION_PER_INPUT_BYTE`] per input
/// byte: room for fixed tables and buffers (a SCIP reply buffer is under
/// 1 MB), far below what a length read from the input and trusted unchecked
/// asks for (gigabytes).
pub const ALLOCATION_BASE: usize = 64 << 20;
/// Heap a decode may allocate per input byte: decompression (LZF expands at
/// most about 90 times) and the per-point structures built from it.
pub const ALLOCATION_PER_INPUT_BYTE: usize = 1024;

/// Runs `decode` and panics if its peak heap use exceeds the bound for an
/// input of `input_len` bytes. Checks nothing unless the process's global
/// allocator is [`metrics::CountingAllocator`] (the fuzzer binaries and the
/// corpus replay install it).
pub fn bounded_allocation(input_len: usize, decode: impl FnOnce()) {
    metrics::reset_peak();
    let before = metrics::live_bytes();
    decode();
    if !metrics::is_counting() {
        return;
    }
    let peak = metrics::peak_bytes().saturating_sub(before);
    let bound = ALLOCATION_BASE + ALLOCATION_PER_INPUT_BYTE * input_len;
    assert!(
        peak <= bound,
        "decoding {input_len} bytes allocated {peak} bytes at peak (bound {bound})"
    );
}

/// An error's message must say something (every decoder error names its problem).
pub fn named(error: &impl Display) {
    let text = error.to_string();
    assert!(!text.trim().is_empty(), "an error with an empty message");
}

/// `a` and `b` must be the same value, compared through `Debug` so that NaN
/// equals NaN and types without `PartialEq` compare too.
#[track_caller]
pub fn same(a: &impl Debug, b: &impl Debug, what: &str) {
    let (a, b) = (format!("{a:?}"), format!("{b:?}"));
    assert!(a == b, "{what} differ:\n  {a}\n  {b}");
}

/// A stream input: the first byte chooses how [`Chunks`] cuts the rest.
pub fn stream(data: &[u8]) -> (u8, &[u8]) {
    match data.split_first() {
        Some((&seed, rest)) => (seed, rest),
        None => (0, &[]),
    }
}

/// The cuts of a byte stream into chunks of pseudo-random lengths (empty
/// chunks included), chosen by a seed byte so that the fuzzer explores them.
pub struct Chunks<'a> {
    rest: &'a [u8],
    state: u32,
    longest: usize,
}

impl<'a> Chunks<'a> {
    pub fn new(seed: u8, bytes: &'a [u8]) -> Self {
        Self {
            rest: bytes,
            state: u32::from(seed).wrapping_mul(0x9E37_79B9) | 1,
            // Seeds 0..=255 give chunks of up to 1..=256 bytes (and 0-byte ones).
            longest: usize::from(seed) + 1,
        }
    }
}

impl<'a> Iterator for Chunks<'a> {
    type Item = &'a [u8];

    fn next(&mut self) -> Option<&'a [u8]> {
        if self.rest.is_empty() {
            return None;
        }
        // xorshift32 (Marsaglia 2003): cheap and deterministic.
        self.state ^= self.state << 13;
        self.state ^= self.state >> 17;
        self.state ^= self.state << 5;
        let len = (self.state as usize % (self.longest + 1)).min(self.rest.len());
        let (chunk, rest) = self.rest.split_at(len);
        self.rest = rest;
        Some(chunk)
    }
}
