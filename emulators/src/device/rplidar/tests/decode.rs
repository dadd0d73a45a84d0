//! Test-side RPLIDAR decoding, written from the protocol text (sensors.md
//! §1.2 and the PDF), not from the emulator's encoders: descriptors, standard
//! nodes, and legacy / dense capsules decoded in floating point.

/// A response descriptor: answer length, looping, answer type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Descriptor {
    pub len: u32,
    pub looping: bool,
    pub answer_type: u8,
}

pub fn descriptor(bytes: &[u8]) -> Option<Descriptor> {
    match bytes {
        [0xA5, 0x5A, w0, w1, w2, w3, answer_type, ..] => {
            let word = u32::from_le_bytes([*w0, *w1, *w2, *w3]);
            Some(Descriptor {
                len: word & 0x3FFF_FFFF,
                looping: word >> 30 == 1,
                answer_type: *answer_type,
            })
        }
        _ => None,
    }
}

/// A decoded standard node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Node {
    pub quality: u8,
    pub start: bool,
    pub angle_deg: f64,
    pub distance_mm: f64,
    /// The check bit and the S / !S pair are consistent.
    pub valid: bool,
}

pub fn node(bytes: &[u8; 5]) -> Node {
    let start = bytes[0] & 1 == 1;
    let not_start = (bytes[0] >> 1) & 1 == 1;
    let check = bytes[1] & 1 == 1;
    let angle_q6 = (u16::from(bytes[1]) >> 1) | (u16::from(bytes[2]) << 7);
    Node {
        quality: bytes[0] >> 2,
        start,
        angle_deg: f64::from(angle_q6) / 64.0,
        distance_mm: f64::from(u16::from_le_bytes([bytes[3], bytes[4]])) / 4.0,
        valid: check && (start != not_start),
    }
}

/// A capsule framed by its sync nibbles, checksum checked.
#[derive(Debug, Clone, PartialEq)]
pub struct Capsule {
    pub start_deg: f64,
    pub new_scan: bool,
    pub checksum_ok: bool,
    pub body: Vec<u8>,
}

pub fn capsule(bytes: &[u8]) -> Option<Capsule> {
    if bytes.len() != 84 || bytes[0] >> 4 != 0xA || bytes[1] >> 4 != 0x5 {
        return None;
    }
    let expected = (bytes[0] & 0x0F) | (bytes[1] << 4);
    let actual = bytes[2..].iter().fold(0u8, |acc, b| acc ^ b);
    let start = u16::from_le_bytes([bytes[2], bytes[3]]);
    Some(Capsule {
        start_deg: f64::from(start & 0x7FFF) / 64.0,
        new_scan: start & 0x8000 != 0,
        checksum_ok: expected == actual,
        body: bytes[4..].to_vec(),
    })
}

/// The 32 (distance mm, dθ degrees) pairs of a legacy capsule.
pub fn legacy_samples(capsule: &Capsule) -> Vec<(f64, f64)> {
    let mut samples = Vec::new();
    for cabin in capsule.body.chunks_exact(5) {
        let d1 = u16::from_le_bytes([cabin[0], cabin[1]]);
        let d2 = u16::from_le_bytes([cabin[2], cabin[3]]);
        let theta1 = (cabin[4] & 0x0F) | ((d1 as u8 & 0x03) << 4);
        let theta2 = (cabin[4] >> 4) | ((d2 as u8 & 0x03) << 4);
        samples.push((f64::from(d1 >> 2), f64::from(theta1) / 8.0));
        samples.push((f64::from(d2 >> 2), f64::from(theta2) / 8.0));
    }
    samples
}

/// The 40 distances (mm) of a dense capsule.
pub fn dense_distances(capsule: &Capsule) -> Vec<f64> {
    capsule
        .body
        .chunks_exact(2)
        .map(|pair| f64::from(u16::from_le_bytes([pair[0], pair[1]])))
        .collect()
}

/// Decodes consecutive capsules into (angle°, distance mm) points: sample k
/// of capsule i lies at start_i + k·(start_{i+1} − start_i mod 360)/n −
/// dθ_k (dθ unsigned; 0 for dense).
pub fn points(capsules: &[Capsule], dense: bool) -> Vec<(f64, f64)> {
    let mut points = Vec::new();
    for pair in capsules.windows(2) {
        let (current, next) = (&pair[0], &pair[1]);
        let diff = (next.start_deg - current.start_deg).rem_euclid(360.0);
        let samples: Vec<(f64, f64)> = if dense {
            dense_distances(current)
                .into_iter()
                .map(|d| (d, 0.0))
                .collect()
        } else {
            legacy_samples(current)
        };
        let n = samples.len() as f64;
        for (k, (distance, dtheta)) in samples.into_iter().enumerate() {
            let angle = (current.start_deg + diff * k as f64 / n - dtheta).rem_euclid(360.0);
            points.push((angle, distance));
        }
    }
    points
}

/// Splits a loop stream after its descriptor into capsules, sliding one
/// byte whenever 84 bytes do not frame a capsule with a good checksum.
/// Returns the capsules and, for each, how many bytes were skipped before it.
pub fn resync_capsules(stream: &[u8]) -> Vec<(usize, Capsule)> {
    let mut found = Vec::new();
    let mut pos = 0;
    let mut skipped = 0;
    while pos + 84 <= stream.len() {
        match capsule(&stream[pos..pos + 84]) {
            Some(c) if c.checksum_ok => {
                found.push((skipped, c));
                skipped = 0;
                pos += 84;
            }
            _ => {
                skipped += 1;
                pos += 1;
            }
        }
    }
    found
}
