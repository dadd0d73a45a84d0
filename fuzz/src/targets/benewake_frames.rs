//! Benewake serial frames below the driver (`benewake::Decoder`): data
//! frames and command replies, independent of chunking, every byte either
//! in a packet, skipped (and counted) or buffered.

use crate::check::{same, stream, Chunks};
use shroud_drivers::benewake::{encode_frame, Command, Decoder};

pub fn run(data: &[u8]) {
    let (seed, bytes) = stream(data);
    let (mut whole, mut all) = (Decoder::new(), Vec::new());
    whole.feed(bytes, &mut all);
    let (mut chunked, mut pieces) = (Decoder::new(), Vec::new());
    Chunks::new(seed, bytes).for_each(|c| chunked.feed(c, &mut pieces));
    same(
        &all,
        &pieces,
        "packets of the whole stream and of its chunks",
    );
    assert_eq!(
        whole.skipped_bytes(),
        chunked.skipped_bytes(),
        "skipped bytes"
    );
    assert_eq!(whole.buffered(), chunked.buffered(), "buffered bytes");
    let skipped_or_used = whole.skipped_bytes() as usize + whole.buffered();
    assert!(
        skipped_or_used <= bytes.len(),
        "more bytes skipped than fed"
    );
}

pub fn seeds() -> Vec<Vec<u8>> {
    let data_frame = |distance: u16, strength: u16| {
        let mut f = vec![0x59, 0x59];
        f.extend(distance.to_le_bytes());
        f.extend(strength.to_le_bytes());
        f.extend([0x00, 0x09]);
        f.push(f.iter().fold(0u8, |a, &b| a.wrapping_add(b)));
        f
    };
    let mut bytes = b"\x00\x59tail".to_vec();
    bytes.extend(data_frame(123, 2000));
    bytes.extend(Command::FrameRate(100).encode());
    bytes.extend(encode_frame(0x01, &[3, 2, 1]));
    bytes.extend(data_frame(65535, 10));
    vec![
        crate::seeds::stream(2, &bytes),
        crate::seeds::stream(30, &bytes),
    ]
}
