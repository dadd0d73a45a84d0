//! RPLIDAR answers below the driver (`ResponseReader`): descriptors and
//! single answers, the same events and stray counts whatever the chunking.

use crate::check::{same, stream, Chunks};
use shroud_drivers::rplidar::reader::{ReaderEvent, ResponseReader};

pub fn run(data: &[u8]) {
    let (seed, bytes) = stream(data);
    let whole = read([bytes].into_iter());
    let chunked = read(Chunks::new(seed, bytes));
    same(
        &whole,
        &chunked,
        "events and stray bytes of the whole stream and of its chunks",
    );
    assert!(whole.1 <= bytes.len() as u64, "more stray bytes than fed");
}

/// The events and the stray byte count of a stream fed in `chunks`.
fn read<'a>(chunks: impl Iterator<Item = &'a [u8]>) -> (Vec<ReaderEvent>, u64) {
    let (mut reader, mut events, mut stray) = (ResponseReader::default(), Vec::new(), 0);
    for mut chunk in chunks {
        while !chunk.is_empty() {
            let fed = reader.feed(chunk);
            assert!(
                fed.consumed > 0 && fed.consumed <= chunk.len(),
                "consumed {} of {}",
                fed.consumed,
                chunk.len()
            );
            stray += fed.stray;
            events.extend(fed.event);
            chunk = &chunk[fed.consumed..];
        }
    }
    (events, stray)
}

pub fn seeds() -> Vec<Vec<u8>> {
    let mut bytes = vec![0x00, 0xA5];
    // GET_HEALTH: a 3-byte single answer of type 0x06 (status, error code).
    bytes.extend([0xA5, 0x5A, 0x03, 0x00, 0x00, 0x00, 0x06, 0x00, 0x00, 0x00]);
    // GET_INFO: 20 bytes of type 0x04 (model, firmware, hardware, serial).
    bytes.extend([0xA5, 0x5A, 0x14, 0x00, 0x00, 0x00, 0x04]);
    bytes.extend((0..20).map(|i| i as u8 * 13));
    // SCAN: a multiple-answer descriptor of 5-byte nodes (mode bits 0b01).
    bytes.extend([0xA5, 0x5A, 0x05, 0x00, 0x00, 0x40, 0x81]);
    vec![
        crate::seeds::stream(4, &bytes),
        crate::seeds::stream(90, &bytes),
    ]
}
