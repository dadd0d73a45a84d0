//! LZF, the compression of PCD `binary_compressed` bodies (Marc Lehmann's
//! liblzf format, which PCL's `pcl::lzfCompress` writes). The `lzf` crate does
//! the work; this file adds the bounds a reader of untrusted sizes needs and a
//! literal-only encoding for data the crate declines to compress.

/// Largest uncompressed body read or written: the `lzf` crate's decoder
/// computes output positions in `i32`, so larger outputs would be refused as
/// corrupt.
pub const MAX_UNCOMPRESSED: usize = i32::MAX as usize;

/// LZF's largest expansion: its longest back reference takes 3 bytes (a control
/// byte of length 7, a length byte of 255, an offset byte) and copies
/// 7 + 255 + 2 = 264 bytes; a literal run never expands. A stream of `n` bytes
/// therefore decodes to at most `88 n` bytes.
pub const MAX_RATIO: usize = 88;

/// Longest literal run: the control byte's low 5 bits hold its length - 1.
const MAX_LITERAL_RUN: usize = 32;

/// `data` compressed. The `lzf` crate refuses data that would not shrink (and
/// inputs under 2 bytes); those are stored as literal runs, which any LZF
/// decoder reads, as PCL's `lzfDecompress` does.
pub fn compress(data: &[u8]) -> Vec<u8> {
    lzf::compress(data).unwrap_or_else(|_| literal_runs(data))
}

/// `data` as LZF literal runs only: each run of up to 32 bytes is preceded by a
/// control byte holding its length - 1.
pub fn literal_runs(data: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(data.len() + data.len().div_ceil(MAX_LITERAL_RUN));
    for run in data.chunks(MAX_LITERAL_RUN) {
        out.push((run.len() - 1) as u8);
        out.extend_from_slice(run);
    }
    out
}

/// The `expected` bytes `data` decodes to, or why it cannot: it is corrupt,
/// or decodes to more or fewer bytes. The caller bounds `expected` by
/// [`MAX_UNCOMPRESSED`] and `MAX_RATIO * data.len()` before calling, since
/// the output is allocated at that size.
pub fn decompress(data: &[u8], expected: usize) -> Result<Vec<u8>, String> {
    if data.is_empty() {
        return exact(Vec::new(), expected);
    }
    let decoded = lzf::decompress(data, expected).map_err(|e| match e {
        lzf::LzfError::BufferTooSmall => {
            format!("the LZF data decodes to more than the {expected} bytes announced")
        }
        other => format!("the LZF data is corrupt ({other})"),
    })?;
    exact(decoded, expected)
}

fn exact(decoded: Vec<u8>, expected: usize) -> Result<Vec<u8>, String> {
    if decoded.len() == expected {
        Ok(decoded)
    } else {
        Err(format!(
            "the LZF data decodes to {} bytes, {expected} were announced",
            decoded.len()
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn literal_runs_are_valid_lzf() {
        for len in [0usize, 1, 2, 31, 32, 33, 64, 100] {
            let data: Vec<u8> = (0..len).map(|i| (i * 37 % 251) as u8).collect();
            let runs = literal_runs(&data);
            assert_eq!(runs.len(), len + len.div_ceil(32), "{len}");
            assert_eq!(decompress(&runs, len), Ok(data), "{len}");
        }
        assert_eq!(literal_runs(b"abc"), b"\x02abc");
    }

    #[test]
    fn compresses_repetitive_and_random_data() {
        let repetitive = [7u8; 5000];
        let packed = compress(&repetitive);
        assert!(packed.len() < 200, "{}", packed.len());
        assert_eq!(decompress(&packed, 5000).unwrap(), repetitive);
        let noise: Vec<u8> = (0..257u32)
            .map(|i| (i.wrapping_mul(2_654_435_761) >> 13) as u8)
            .collect();
        assert_eq!(decompress(&compress(&noise), noise.len()).unwrap(), noise);
        assert_eq!(compress(b"x"), b"\x00x");
    }

    #[test]
    fn the_ratio_bound_is_reached_and_not_exceeded() {
        // One literal byte, then a back reference of offset 1 and the longest
        // length: 2 + 3 bytes decode to 1 + 264.
        let longest = [0x00, b'a', 0xe0, 0xff, 0x00];
        assert_eq!(decompress(&longest, 265).unwrap(), vec![b'a'; 265]);
        assert!(265 <= MAX_RATIO * longest.len());
    }

    #[test]
    fn bad_streams_are_errors() {
        assert!(decompress(&[0x05, 1, 2], 6)
            .unwrap_err()
            .contains("corrupt"));
        assert!(decompress(&[0x02, 1, 2, 3], 2)
            .unwrap_err()
            .contains("more than the 2 bytes"));
        assert!(decompress(&[0x01, 1, 2], 3)
            .unwrap_err()
            .contains("decodes to 2 bytes"));
        assert!(decompress(&[0x20, 0x00], 10)
            .unwrap_err()
            .contains("corrupt"));
        assert!(decompress(&[], 1)
            .unwrap_err()
            .contains("decodes to 0 bytes"));
    }
}
