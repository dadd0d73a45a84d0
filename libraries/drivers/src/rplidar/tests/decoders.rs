//! Stream decoders, the revolution assembler, the reply reader and the
//! timing model, one behaviour per test.

use super::sim::*;
use crate::device::DeviceStats;
use crate::rplidar::reader::{ReaderEvent, RejectReason, ResponseReader};
use crate::rplidar::revolution::RevolutionAssembler;
use crate::rplidar::stream::{SampleFormat, StreamDecoder};
use crate::rplidar::timing::SampleClock;

#[test]
fn standard_stream_gives_whole_revolutions_and_drops_the_first_partial() {
    let bytes = standard_stream(3, 360, 1);
    let (revs, stats) = decode(SampleFormat::Standard, &[&bytes]);
    assert_eq!(revs.len(), 3);
    assert!(revs.iter().all(|r| r.rays.len() == 360));
    assert_eq!(stats.notes("partial_revolution"), 1);
    assert_eq!(stats.total_errors(), 0);
}

#[test]
fn garbage_before_the_stream_is_counted_as_resync() {
    let mut bytes = vec![0x00, 0x03, 0xFF];
    bytes.extend(standard_stream(2, 100, 2));
    let (revs, stats) = decode(SampleFormat::Standard, &[&bytes]);
    assert_eq!(revs.len(), 2);
    assert_eq!(stats.errors("resync"), 3);
}

#[test]
fn a_lost_byte_drops_its_revolution_whole() {
    let per_rev = 100;
    let mut bytes = standard_stream(3, per_rev, 3);
    // Remove one byte in the middle of the second complete revolution.
    let second_rev_node = per_rev / 3 + per_rev + per_rev / 2;
    bytes.remove(second_rev_node * 5 + 3);
    let (revs, stats) = decode(SampleFormat::Standard, &[&bytes]);
    assert_eq!(stats.errors("incomplete_scan"), 1);
    assert!(stats.errors("resync") >= 1);
    assert!(
        revs.iter().all(|r| r.rays.len() == per_rev),
        "no holes: {:?} {}",
        revs.iter().map(|r| r.rays.len()).collect::<Vec<_>>(),
        stats
    );
    assert_eq!(revs.len(), 2);
}

#[test]
fn express_stream_revolutions_are_about_one_turn() {
    let bytes = express_stream(3, 4);
    let (revs, stats) = decode(SampleFormat::Express, &[&bytes]);
    // 24 capsules of 32 samples a turn.
    assert!(revs.len() >= 3);
    assert!(
        revs.iter().all(|r| r.rays.len() == 24 * 32),
        "{:?}",
        revs.iter().map(|r| r.rays.len()).collect::<Vec<_>>()
    );
    assert_eq!(stats.notes("partial_revolution"), 1);
    assert_eq!(stats.total_errors(), 0);
}

#[test]
fn express_checksum_failure_drops_the_revolution() {
    let mut bytes = express_stream(3, 5);
    let clean = decode(SampleFormat::Express, &[&bytes]).0.len();
    // Corrupt a distance byte of capsule 40 (inside a full revolution).
    bytes[40 * 84 + 10] ^= 0x40;
    let (revs, stats) = decode(SampleFormat::Express, &[&bytes]);
    assert_eq!(stats.errors("bad_checksum"), 1);
    assert!(stats.errors("incomplete_scan") >= 1);
    assert!(revs.len() < clean);
    assert!(revs.iter().all(|r| r.rays.len() == 24 * 32));
}

#[test]
fn express_restart_mid_revolution_counts_a_partial() {
    let bytes = express_stream(2, 6);
    let mut restarted = bytes[..40 * 84].to_vec();
    restarted.extend(express_stream(2, 7));
    let (revs, stats) = decode(SampleFormat::Express, &[&restarted]);
    assert_eq!(
        stats.notes("partial_revolution"),
        3,
        "start, mid-turn restart, its partial"
    );
    assert!(revs.iter().all(|r| r.rays.len() == 24 * 32));
}

#[test]
fn dense_stream_and_implausible_span() {
    let bytes = dense_stream(2, 8);
    let (revs, stats) = decode(SampleFormat::Dense, &[&bytes]);
    assert!(revs.len() >= 2);
    assert!(revs.iter().all(|r| r.rays.len() == 18 * 40));
    assert_eq!(stats.total_errors(), 0);
    assert_eq!(
        stats.notes("partial_revolution"),
        1,
        "only the first partial"
    );

    // At 125 µs a sample, 40 samples at 100 Hz span 180°: a 200° jump is lost.
    let a = dense_capsule(0, false, &[100; 40]);
    let b = dense_capsule(200 * 64, false, &[100; 40]);
    let (_, stats) = decode(SampleFormat::Dense, &[&[a, b].concat()]);
    assert_eq!(stats.errors("capsule_gap"), 1);
}

#[test]
fn oversize_revolutions_are_dropped() {
    let bytes = standard_stream(3, 200, 9);
    let mut decoder = StreamDecoder::new(SampleFormat::Standard, clock());
    let mut assembler = RevolutionAssembler::new(150, 8);
    let (mut stats, mut events, mut revs) = (DeviceStats::default(), Vec::new(), Vec::new());
    decoder.feed(&bytes, t(0), &mut stats, &mut events);
    for e in events {
        revs.extend(assembler.push(e, &mut stats));
    }
    assert!(revs.is_empty());
    assert_eq!(stats.errors("oversize_scan"), 3);
}

#[test]
fn sample_times_follow_the_sdk_delay_model() {
    let clock = SampleClock::new(125 << 8, 256_000);
    // Standard node: 125 µs + 62.5 µs + 5 bytes · 10 bits / 256000 baud (195.3125 µs).
    assert_eq!(
        clock.sample_time(1_000_000_000, 5, 1, 0),
        1_000_000_000 - 125_000 - 62_500 - 195_312
    );
    // Express sample 0 of 32 in an 84-byte capsule: + 31 later samples.
    let transmission = 84 * 10_000_000_000u64 / 256_000;
    assert_eq!(
        clock.sample_time(1_000_000_000, 84, 32, 0),
        1_000_000_000 - 125_000 - 62_500 - transmission - 31 * 125_000
    );
    assert_eq!(clock.sample_time(10, 84, 32, 0), 0, "saturates");
}

#[test]
fn scan_stamp_is_the_first_ray_and_offsets_are_monotone() {
    let bytes = express_stream(2, 10);
    // Deliver the capsules in irregular chunks at increasing times.
    let mut decoder = StreamDecoder::new(SampleFormat::Express, clock());
    let mut assembler = RevolutionAssembler::new(8192, 0);
    let (mut stats, mut events, mut revs) = (DeviceStats::default(), Vec::new(), Vec::new());
    for (i, chunk) in bytes.chunks(250).enumerate() {
        decoder.feed(chunk, t(i as u64 * 3), &mut stats, &mut events);
        for e in events.drain(..) {
            revs.extend(assembler.push(e, &mut stats));
        }
    }
    assert!(!revs.is_empty());
    for rev in &revs {
        assert_eq!(rev.rays[0].offset_ns, 0);
        assert!(rev
            .rays
            .windows(2)
            .all(|w| w[0].offset_ns <= w[1].offset_ns));
        assert!(rev.stamp_ns < t(1000).unix_ns && rev.stamp_ns > t(0).unix_ns - 1_000_000_000);
    }
}

#[test]
fn reader_cuts_answers_and_counts_stray_bytes() {
    let mut reader = ResponseReader::default();
    let mut bytes = vec![0x00, 0xA5, 0xA5, 0x11];
    bytes.extend(reply(0x06, &[0, 0, 0]));
    let fed = reader.feed(&bytes);
    assert_eq!(fed.stray, 4);
    assert_eq!(fed.consumed, bytes.len());
    assert_eq!(
        fed.event,
        Some(ReaderEvent::Reply {
            answer_type: 0x06,
            payload: vec![0, 0, 0]
        })
    );
    let fed = reader.feed(&descriptor(1000, false, 0x04));
    assert_eq!(
        fed.event,
        Some(ReaderEvent::Rejected(RejectReason::TooLong(1000)))
    );
    let mut stream = descriptor(84, true, 0x82);
    stream.extend([1, 2, 3]);
    let fed = reader.feed(&stream);
    assert_eq!(
        fed.consumed, 7,
        "the stream's bytes are left for the decoder"
    );
    assert!(matches!(fed.event, Some(ReaderEvent::Stream(d)) if d.answer_type == 0x82));
}
