//! shroud's serial range-sensor frames (`SerialScanDecoder`, docs/sensor-protocols.md
//! §1): scans and errors do not depend on how the stream is chunked, and a
//! decoded scan, encoded again, decodes the same.

use crate::check::{named, same, stream, Chunks};
use shroud_drivers::serial::{PointEncoding, SerialEncoder, SerialScanDecoder};
use shroud_drivers::{IngestError, Scan};

pub fn run(data: &[u8]) {
    let (seed, bytes) = stream(data);
    let mut whole = SerialScanDecoder::default();
    let mut results = whole.push(bytes);
    results.extend(whole.finish());
    let mut chunked = SerialScanDecoder::default();
    let mut pieces: Vec<_> = Chunks::new(seed, bytes)
        .flat_map(|c| chunked.push(c))
        .collect();
    pieces.extend(chunked.finish());
    same(
        &results,
        &pieces,
        "results of the whole stream and of its chunks",
    );
    same(
        whole.stats(),
        chunked.stats(),
        "counts of the whole stream and of its chunks",
    );
    for result in &results {
        match result {
            Ok(scan) => same(
                &vec![scan.clone()],
                &decode(&encode(scan)),
                "scans after a round trip",
            ),
            Err(e) => named(e),
        }
    }
}

fn encode(scan: &Scan) -> Vec<u8> {
    SerialEncoder::default()
        .encode(scan)
        .expect("a decoded scan encodes")
}

fn decode(bytes: &[u8]) -> Vec<Scan> {
    let mut decoder = SerialScanDecoder::default();
    let mut out = decoder.push(bytes);
    out.extend(decoder.finish());
    out.into_iter()
        .collect::<Result<Vec<_>, IngestError>>()
        .expect("an encoded scan decodes")
}

pub fn seeds() -> Vec<Vec<u8>> {
    let mut scan = Scan::new(
        9,
        1_700_000_000_000_000_000,
        vec![[1.0, -2.0, 0.5], [0.25, 0.0, 3.0], [0.0, 0.0, 0.0]],
    );
    let plain = SerialEncoder::new(PointEncoding::I16Millimetres, 2).encode(&scan);
    scan.intensity = Some(vec![10.0, 20.0, 30.0]);
    let rich = SerialEncoder::new(PointEncoding::I32Millimetres, 1).encode(&scan);
    let metres = SerialEncoder::default().encode(&scan);
    let mut seeds = Vec::new();
    for bytes in [plain, rich, metres] {
        let mut bytes = bytes.expect("the seed scan encodes");
        seeds.push(crate::seeds::stream(5, &bytes));
        let mut after_garbage = b"garbage\xAA".to_vec();
        after_garbage.append(&mut bytes);
        seeds.push(crate::seeds::stream(200, &after_garbage));
    }
    seeds
}
