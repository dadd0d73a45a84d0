//! SCIP 2.0 replies below the driver: lines (`LineSplitter`) grouped into
//! replies (`ReplyAssembler`) independently of chunking; then each reply's
//! status line, parameter pairs and, for a measurement echo, its scan data
//! (`decode_scan`), which re-encodes and decodes the same.

use crate::check::{named, same, stream, Chunks};
use shroud_drivers::scip::{
    decode_scan, encode, line_sum, parse_pairs, Assembled, LineSplitter, Reply, ReplyAssembler,
    ScanKind, ScanRequest, Status,
};

pub fn run(data: &[u8]) {
    let (seed, bytes) = stream(data);
    let whole = assemble([bytes].into_iter());
    same(
        &whole,
        &assemble(Chunks::new(seed, bytes)),
        "replies of the whole stream and of its chunks",
    );
    for reply in whole.iter().filter_map(|a| match a {
        Assembled::Reply(r) => Some(r),
        Assembled::Overflow => None,
    }) {
        check(reply);
    }
}

fn assemble<'a>(chunks: impl Iterator<Item = &'a [u8]>) -> Vec<Assembled> {
    let (mut lines, mut replies) = (LineSplitter::new(), ReplyAssembler::new());
    chunks
        .flatten()
        .filter_map(|&b| lines.push(b))
        .filter_map(|line| replies.push(line))
        .collect()
}

fn check(reply: &Reply) {
    let Some((status, rest)) = reply.lines.split_first() else {
        return;
    };
    if let Err(e) = Status::parse(status) {
        assert!(
            !e.kind().is_empty(),
            "a status error without a counter name"
        );
    }
    if let Err(e) = parse_pairs(rest) {
        named(&e);
    }
    let Some(request) = request_of(&reply.echo) else {
        return;
    };
    match decode_scan(rest, &request) {
        Ok(scan) if !request.kind.is_multiecho() => {
            let again = decode_scan(&lines_of(&scan, request.kind), &request)
                .expect("re-encoded scan data decodes");
            same(&scan, &again, "scan data after a round trip");
        }
        Ok(_) => {}
        Err(e) => named(&e),
    }
}

const KINDS: [ScanKind; 10] = [
    ScanKind::Md,
    ScanKind::Ms,
    ScanKind::Me,
    ScanKind::Gd,
    ScanKind::Gs,
    ScanKind::Ge,
    ScanKind::Nd,
    ScanKind::Ne,
    ScanKind::Hd,
    ScanKind::He,
];

/// The measurement request an echo repeats (`MD0044072501000`: kind, start,
/// end, cluster, then interval and scans for streamed kinds).
fn request_of(echo: &[u8]) -> Option<ScanRequest> {
    let text = std::str::from_utf8(echo).ok()?;
    let kind = KINDS.into_iter().find(|k| text.starts_with(k.symbol()))?;
    let number = |range: std::ops::Range<usize>| text.get(range)?.parse::<u16>().ok();
    let request = ScanRequest {
        kind,
        start: number(2..6)?,
        end: number(6..10)?,
        cluster: u8::try_from(number(10..12)?).ok()?,
        interval: 0,
        scans: 0,
    };
    request.validate().ok().map(|()| request)
}

/// A single-echo scan's data lines as a sensor sends them: the timestamp,
/// then the values cut into 64-character lines, each with its sum.
fn lines_of(scan: &shroud_drivers::scip::ScanData, kind: ScanKind) -> Vec<Vec<u8>> {
    let summed = |mut body: Vec<u8>| {
        body.push(line_sum(&body));
        body
    };
    let width = kind.range_width();
    let value = |v: u32, w: usize| encode(v, w).expect("a decoded value fits its width");
    let text: Vec<u8> = match &scan.intensities {
        Some(intensity) => scan
            .ranges
            .iter()
            .zip(intensity)
            .flat_map(|(&r, &i)| [value(r, width), value(i, width)].concat())
            .collect(),
        None => scan.ranges.iter().flat_map(|&r| value(r, width)).collect(),
    };
    let mut lines = vec![summed(value(scan.timestamp_ms, 4))];
    lines.extend(text.chunks(64).map(|c| summed(c.to_vec())));
    lines
}

pub fn seeds() -> Vec<Vec<u8>> {
    let line = |body: &str| {
        let mut l = body.as_bytes().to_vec();
        l.push(line_sum(body.as_bytes()));
        l.push(b'\n');
        l
    };
    let ranges: Vec<u8> = (0..21u32)
        .flat_map(|i| encode(300 + 7 * i, 3).expect("fits"))
        .collect();
    let mut md = b"MD0000002001000\n".to_vec();
    md.extend(line("99"));
    md.extend(line(
        std::str::from_utf8(&encode(123_456, 4).expect("fits")).expect("ASCII"),
    ));
    for chunk in ranges.chunks(64) {
        md.extend(line(std::str::from_utf8(chunk).expect("ASCII")));
    }
    md.push(b'\n');
    // The status `00` and its sum `P`; a parameter line's sum covers `KEY:VALUE`.
    let mut pp = b"PP\n00P\nMODL:URG-04LX;".to_vec();
    pp.push(line_sum(b"MODL:URG-04LX"));
    pp.extend_from_slice(b"\nDMIN:20;4\n\n");
    vec![
        crate::seeds::stream(3, &md),
        crate::seeds::stream(40, &pp),
        crate::seeds::stream(0, b"QT\r\n00P\r\n\r\n"),
    ]
}
