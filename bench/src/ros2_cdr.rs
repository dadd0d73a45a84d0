//! `shroud-bench ros2-cdr`: shroud's hand-written CDR codec (`shroud-ros2`)
//! against the two maintained serde CDR crates a Rust ROS 2 user would pick
//! (`cdr`, which zenoh's ROS 2 plugin uses, and `cdr-encoding`, RustDDS's),
//! on one `sensor_msgs/PointCloud2` of `--points` points (xyz + intensity,
//! float32, 16 bytes a point), beside the floor any owned decode pays: one
//! copy of the payload.
//!
//! Every decoder's result is checked against the cloud that was encoded
//! before anything is timed, so a faster row cannot be a wrong one.

use super::{median, BenchArgs};
use anyhow::{ensure, Context, Result};
use serde::{Deserialize, Serialize};
use serde_bytes::ByteBuf;
use shroud_ros2::msgs::{Header, PointCloud2, PointField, Time};
use shroud_ros2::RosMessage;
use shroud_ros2_bridge::{cloud_from_ros, CloudMount};
use std::borrow::Cow;
use std::hint::black_box;
use std::time::Instant;

/// Bytes a point: x, y, z, intensity as float32.
const POINT_STEP: u32 = 16;
/// Timed repetitions of each row, full and `--quick`.
const RUNS: usize = 101;
const QUICK_RUNS: usize = 5;

/// PointCloud2 as a serde user writes it, `data` either a plain `Vec<u8>`
/// (which a derive reads byte by byte) or a `serde_bytes::ByteBuf` (one byte
/// string, the fast path both crates offer).
#[derive(Debug, PartialEq, Serialize, Deserialize)]
struct SerdeCloud<Data> {
    header: SerdeHeader,
    height: u32,
    width: u32,
    fields: Vec<SerdeField>,
    is_bigendian: bool,
    point_step: u32,
    row_step: u32,
    data: Data,
    is_dense: bool,
}

type BytesCloud = SerdeCloud<ByteBuf>;
type PlainCloud = SerdeCloud<Vec<u8>>;

#[derive(Debug, PartialEq, Serialize, Deserialize)]
struct SerdeHeader {
    sec: i32,
    nanosec: u32,
    frame_id: String,
}

#[derive(Debug, PartialEq, Serialize, Deserialize)]
struct SerdeField {
    name: String,
    offset: u32,
    datatype: u8,
    count: u32,
}

/// Most points a cloud here may have: its data length must fit the
/// message's u32 `row_step`.
const MAX_POINTS: usize = (u32::MAX / POINT_STEP) as usize;

pub fn run(args: &BenchArgs) -> Result<()> {
    let points = args.points;
    ensure!(
        (1..=MAX_POINTS).contains(&points),
        "--points must be in [1, {MAX_POINTS}] for one PointCloud2"
    );
    let runs = if args.quick { QUICK_RUNS } else { RUNS };
    let cloud = test_cloud(points);
    let payload = cloud.encode();
    let expected = BytesCloud::of(&cloud);
    check_decoders(&payload, &cloud, &expected)?;

    let rows = [
        time_row("payload copy (the floor of an owned decode)", runs, || {
            black_box(payload.to_vec());
        }),
        time_row("shroud-ros2 decode, data borrowed", runs, || {
            black_box(PointCloud2::decode_borrowed(&payload).expect("checked"));
        }),
        time_row("shroud-ros2 decode, data owned", runs, || {
            black_box(<PointCloud2<'static>>::decode(&payload).expect("checked"));
        }),
        time_row("cdr 0.2.4 (serde_bytes)", runs, || {
            black_box(cdr::deserialize::<BytesCloud>(&payload).expect("checked"));
        }),
        time_row("cdr 0.2.4 (plain Vec<u8>)", runs, || {
            black_box(cdr::deserialize::<PlainCloud>(&payload).expect("checked"));
        }),
        time_row("cdr-encoding 0.11 (serde_bytes)", runs, || {
            black_box(cdr_encoding_decode::<BytesCloud>(&payload).expect("checked"));
        }),
        time_row("cdr-encoding 0.11 (plain Vec<u8>)", runs, || {
            black_box(cdr_encoding_decode::<PlainCloud>(&payload).expect("checked"));
        }),
        time_row("shroud-ros2 encode", runs, || {
            black_box(cloud.encode());
        }),
        time_row("cdr 0.2.4 encode (serde_bytes)", runs, || {
            black_box(
                cdr::serialize::<_, _, cdr::CdrLe>(&expected, cdr::Infinite).expect("checked"),
            );
        }),
        time_row(
            "decode borrowed + cloud_from_ros (the bridge's ingest)",
            runs,
            || {
                let decoded = PointCloud2::decode_borrowed(&payload).expect("checked");
                black_box(
                    cloud_from_ros(&decoded, &CloudMount::default(), "bench", 0).expect("checked"),
                );
            },
        ),
    ];
    print_table(points, payload.len(), runs, &rows);
    Ok(())
}

/// `cdr-encoding` reads the message after the 4-byte encapsulation header
/// (CDR_LE here), which it leaves to its caller.
fn cdr_encoding_decode<T: for<'de> Deserialize<'de>>(payload: &[u8]) -> Result<T> {
    let body = payload
        .get(4..)
        .context("payload shorter than its header")?;
    let (value, _) = cdr_encoding::from_bytes::<T, byteorder::LittleEndian>(body)?;
    Ok(value)
}

/// Each decoder gives back the cloud that was encoded, and the peers'
/// encoding is byte for byte shroud's.
fn check_decoders(payload: &[u8], cloud: &PointCloud2<'_>, expected: &BytesCloud) -> Result<()> {
    let borrowed = PointCloud2::decode_borrowed(payload)?;
    ensure!(
        &borrowed == cloud,
        "shroud-ros2 (borrowed) misread the cloud"
    );
    ensure!(
        &<PointCloud2<'static>>::decode(payload)? == cloud,
        "shroud-ros2 (owned) misread the cloud"
    );
    ensure!(
        &cdr::deserialize::<BytesCloud>(payload)? == expected,
        "cdr misread the cloud"
    );
    let plain = cdr::deserialize::<PlainCloud>(payload)?;
    ensure!(
        plain.data == *expected.data,
        "cdr (plain) misread the cloud"
    );
    ensure!(
        &cdr_encoding_decode::<BytesCloud>(payload)? == expected,
        "cdr-encoding misread the cloud"
    );
    let plain = cdr_encoding_decode::<PlainCloud>(payload)?;
    ensure!(
        expected.data == plain.data,
        "cdr-encoding (plain) misread the cloud"
    );
    let peer_bytes = cdr::serialize::<_, _, cdr::CdrLe>(expected, cdr::Infinite)?;
    ensure!(
        peer_bytes == payload,
        "cdr encodes the cloud differently from shroud-ros2"
    );
    Ok(())
}

impl BytesCloud {
    fn of(cloud: &PointCloud2<'_>) -> Self {
        Self {
            header: SerdeHeader {
                sec: cloud.header.stamp.sec,
                nanosec: cloud.header.stamp.nanosec,
                frame_id: cloud.header.frame_id.clone(),
            },
            height: cloud.height,
            width: cloud.width,
            fields: cloud.fields.iter().map(SerdeField::of).collect(),
            is_bigendian: cloud.is_bigendian,
            point_step: cloud.point_step,
            row_step: cloud.row_step,
            data: ByteBuf::from(cloud.data.to_vec()),
            is_dense: cloud.is_dense,
        }
    }
}

impl SerdeField {
    fn of(field: &PointField) -> Self {
        Self {
            name: field.name.clone(),
            offset: field.offset,
            datatype: field.datatype,
            count: field.count,
        }
    }
}

/// An unorganised cloud of `points` points on a wavy sheet, as a depth
/// sensor's driver publishes one.
fn test_cloud(points: usize) -> PointCloud2<'static> {
    let side = (points as f64).sqrt().ceil().max(1.0) as usize;
    let mut data = Vec::with_capacity(points * POINT_STEP as usize);
    for i in 0..points {
        let (u, v) = (
            (i % side) as f32 / side as f32,
            (i / side) as f32 / side as f32,
        );
        let z = 0.1 * (6.0 * u).sin() * (4.0 * v).cos();
        for value in [u - 0.5, v - 0.5, 1.0 + z, 0.5] {
            data.extend_from_slice(&value.to_le_bytes());
        }
    }
    let field = |name: &str, offset| PointField::scalar(name, offset, PointField::FLOAT32);
    PointCloud2 {
        header: Header {
            stamp: Time {
                sec: 1_700_000_000,
                nanosec: 5,
            },
            frame_id: "camera_depth_optical_frame".into(),
        },
        height: 1,
        width: points as u32,
        fields: vec![
            field("x", 0),
            field("y", 4),
            field("z", 8),
            field("intensity", 12),
        ],
        is_bigendian: false,
        point_step: POINT_STEP,
        row_step: POINT_STEP * points as u32,
        data: Cow::Owned(data),
        is_dense: true,
    }
}

struct Row {
    name: &'static str,
    median_ms: f64,
}

fn time_row(name: &'static str, runs: usize, mut f: impl FnMut()) -> Row {
    f(); // warm the caches and the allocator
    let mut ms: Vec<f64> = (0..runs)
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    Row {
        name,
        median_ms: median(&mut ms),
    }
}

fn print_table(points: usize, bytes: usize, runs: usize, rows: &[Row]) {
    let floor = rows[0].median_ms;
    println!(
        "### One PointCloud2 of {points} points ({:.1} MB), median of {runs} runs, one thread\n",
        bytes as f64 / 1e6
    );
    println!("| codec | median (µs) | x payload copy | GB/s |");
    println!("|---|---:|---:|---:|");
    for row in rows {
        println!(
            "| {} | {:.1} | {:.2} | {:.2} |",
            row.name,
            row.median_ms * 1e3,
            row.median_ms / floor,
            bytes as f64 / (row.median_ms * 1e-3) / 1e9
        );
    }
}
