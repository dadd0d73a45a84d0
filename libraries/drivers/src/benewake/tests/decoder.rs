//! The streaming decoder: resync, bad sums, replies interleaved with frames.

use super::support::frame;
use crate::benewake::{
    encode_frame, Command, CommandFrame, DataFrame, DecodeError, Decoded, Decoder, Packet,
};

fn decode(bytes: &[u8]) -> Vec<Decoded> {
    let mut decoder = Decoder::new();
    let mut out = Vec::new();
    decoder.feed(bytes, &mut out);
    out
}

fn data(distance: u16, strength: u16, aux: u16) -> Decoded {
    Ok(Packet::Data(DataFrame {
        distance,
        strength,
        aux,
    }))
}

fn reply(bytes: &[u8]) -> Decoded {
    Ok(Packet::Reply(CommandFrame::parse(bytes).unwrap()))
}

#[test]
fn back_to_back_frames() {
    let mut bytes = frame(16, 288, 0).to_vec();
    bytes.extend(frame(1000, 5, 2248));
    assert_eq!(decode(&bytes), [data(16, 288, 0), data(1000, 5, 2248)]);
}

#[test]
fn a_bad_sum_is_counted_once_and_the_next_frame_is_found() {
    let mut bad = frame(16, 288, 0);
    bad[8] ^= 0x01;
    let mut bytes = bad.to_vec();
    bytes.extend(frame(17, 289, 0));
    assert_eq!(
        decode(&bytes),
        [Err(DecodeError::BadChecksum), data(17, 289, 0)]
    );
}

#[test]
fn sliding_one_byte_finds_a_frame_that_starts_inside_a_bad_one() {
    // 59 59 59 <valid frame minus its first 59>: the first candidate fails
    // its sum, the one a byte later is good.
    let good = frame(0x0159, 300, 2248);
    let mut bytes = vec![0x59];
    bytes.extend(good);
    let out = decode(&bytes);
    assert_eq!(out.last(), Some(&data(0x0159, 300, 2248)));
    assert_eq!(out.iter().filter(|d| d.is_ok()).count(), 1);
}

#[test]
fn replies_between_frames_are_separated() {
    let version = encode_frame(0x01, &[1, 2, 3]);
    let echo = Command::FrameRate(100).encode();
    let mut bytes = frame(16, 288, 0).to_vec();
    bytes.extend(&version);
    bytes.extend(frame(17, 288, 0));
    bytes.extend(&echo);
    assert_eq!(
        decode(&bytes),
        [
            data(16, 288, 0),
            reply(&version),
            data(17, 288, 0),
            reply(&echo)
        ]
    );
}

#[test]
fn frames_holding_header_bytes_decode() {
    // Distance 0x5A59 / strength 0x5959 put both header bytes in the payload.
    let mut bytes = frame(0x5A59, 0x5959, 0x5A5A).to_vec();
    bytes.extend(frame(0x595A, 0x5A5A, 0x5959));
    assert_eq!(
        decode(&bytes),
        [data(0x5A59, 0x5959, 0x5A5A), data(0x595A, 0x5A5A, 0x5959)]
    );
}

#[test]
fn leading_tail_is_a_partial_frame_later_junk_is_garbage() {
    let whole = frame(16, 288, 0);
    let mut bytes = whole[4..].to_vec();
    bytes.extend(whole);
    bytes.extend([0x00, 0x11, 0x22]);
    bytes.extend(whole);
    assert_eq!(
        decode(&bytes),
        [
            Err(DecodeError::PartialFrame),
            data(16, 288, 0),
            Err(DecodeError::Garbage),
            data(16, 288, 0)
        ]
    );
}

#[test]
fn a_5a_that_is_no_reply_is_garbage_and_costs_no_frame() {
    // 5A with a length of 9 swallows the next frame's bytes as a candidate,
    // fails its sum, and the frame is still found.
    let mut bytes = frame(1, 200, 0).to_vec();
    bytes.extend([0x5A, 0x09]);
    bytes.extend(frame(2, 200, 0));
    bytes.extend([0x5A, 0x02]); // impossible length
    bytes.extend(frame(3, 200, 0));
    assert_eq!(
        decode(&bytes),
        [
            data(1, 200, 0),
            Err(DecodeError::Garbage),
            data(2, 200, 0),
            Err(DecodeError::Garbage),
            data(3, 200, 0)
        ]
    );
}

#[test]
fn endless_noise_keeps_counting_and_stays_bounded() {
    let mut decoder = Decoder::new();
    let mut out = Vec::new();
    decoder.feed(&frame(1, 200, 0), &mut out);
    out.clear();
    decoder.feed(&[0x33; 640], &mut out);
    assert_eq!(out, vec![Err(DecodeError::Garbage); 10]);
    assert_eq!(decoder.skipped_bytes(), 640);
    assert_eq!(decoder.buffered(), 0);
}

#[test]
fn reset_forgets_a_partial_frame() {
    let whole = frame(16, 288, 0);
    let mut decoder = Decoder::new();
    let mut out = Vec::new();
    decoder.feed(&whole[..5], &mut out);
    assert!(out.is_empty());
    assert_eq!(decoder.buffered(), 5);
    decoder.reset();
    decoder.feed(&whole, &mut out);
    assert_eq!(out, [data(16, 288, 0)]);
}
