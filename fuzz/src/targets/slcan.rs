//! SLCAN (Lawicel ASCII) streams (`SlcanDecoder`): the messages do not
//! depend on how the stream is chunked, and every decoded frame written
//! back as a line parses to the same frame.

use crate::check::{named, same, stream, Chunks};
use shroud_drivers::can::slcan::{encode_frame, open_commands, parse_line};
use shroud_drivers::can::{CanFrame, SlcanDecoder, SlcanMessage};

pub fn run(data: &[u8]) {
    let (seed, bytes) = stream(data);
    let mut whole = SlcanDecoder::default();
    let messages = whole.push(bytes);
    let mut chunked = SlcanDecoder::default();
    let pieces: Vec<_> = Chunks::new(seed, bytes)
        .flat_map(|c| chunked.push(c))
        .collect();
    same(
        &messages,
        &pieces,
        "messages of the whole stream and of its chunks",
    );
    same(
        whole.stats(),
        chunked.stats(),
        "counts of the whole stream and of its chunks",
    );
    for message in &messages {
        match message {
            Ok(SlcanMessage::Frame { frame, .. }) => {
                let line = encode_frame(frame);
                let again = parse_line(&line[..line.len() - 1]).expect("a written frame parses");
                match again {
                    SlcanMessage::Frame { frame: f, .. } => {
                        same(frame, &f, "frames after a round trip")
                    }
                    other => panic!("a written frame parsed as {other:?}"),
                }
            }
            Ok(_) => {}
            Err(e) => named(e),
        }
    }
}

pub fn seeds() -> Vec<Vec<u8>> {
    let mut text = open_commands(500_000).expect("a standard bitrate");
    for frame in [
        CanFrame::new(0x123, false, &[0xDE, 0xAD, 0xBE, 0xEF]),
        CanFrame::new(0x1234_5678, true, &[1, 2, 3, 4, 5, 6, 7, 8]),
        CanFrame::remote(0x7FF, false, 2),
    ] {
        text.extend(encode_frame(&frame.expect("a valid seed frame")));
    }
    text.extend_from_slice(b"t12320102EA61\rV1013\r\x07z\r");
    vec![
        crate::seeds::stream(7, &text),
        crate::seeds::stream(0, &text),
    ]
}
