//! A chunk's records, decompressed, checked and walked by shroud rather than
//! by the `mcap` crate's linear reader, which trusts the length of a record
//! inside an uncompressed chunk (one longer than its chunk overflows a
//! subtraction: a panic with debug assertions, garbage without; found by the
//! `mcap_recording` fuzz target). Layout: MCAP specification, "Chunk"
//! (<https://mcap.dev/spec#chunk-op0x06>).

/// Hands each record of the chunk record `chunk` to `each(opcode, data)`
/// in order; `each` returns false to stop (then false is returned). The
/// chunk decompresses to at most `limit` bytes.
pub fn for_each_record<E: From<String>>(
    chunk: &[u8],
    limit: usize,
    mut each: impl FnMut(u8, &[u8]) -> Result<bool, E>,
) -> Result<bool, E> {
    let content = contents(chunk, limit)?;
    let mut rest = content.as_slice();
    while !rest.is_empty() {
        let (head, after) = take(rest, 9)?;
        let len = u64::from_le_bytes(head[1..9].try_into().expect("8 bytes"));
        let (data, after) = take_u64(after, len)?;
        if !each(head[0], data)? {
            return Ok(false);
        }
        rest = after;
    }
    Ok(true)
}

/// The chunk's records, decompressed and checked against its uncompressed
/// size and CRC (when not 0).
fn contents(chunk: &[u8], limit: usize) -> Result<Vec<u8>, String> {
    let (fixed, rest) = take(chunk, 28)?;
    let uncompressed_size = u64::from_le_bytes(fixed[16..24].try_into().expect("8 bytes"));
    let crc = u32::from_le_bytes(fixed[24..28].try_into().expect("4 bytes"));
    let (len, rest) = take(rest, 4)?;
    let (compression, rest) = take_u64(
        rest,
        u64::from(u32::from_le_bytes(len.try_into().expect("4 bytes"))),
    )?;
    let (len, rest) = take(rest, 8)?;
    let (compressed, _) = take_u64(rest, u64::from_le_bytes(len.try_into().expect("8 bytes")))?;
    let size = usize::try_from(uncompressed_size)
        .ok()
        .filter(|&s| s <= limit)
        .ok_or_else(|| format!("a chunk claims {uncompressed_size} bytes uncompressed, above the {limit} this file allows"))?;
    let content = match compression {
        b"" => compressed.to_vec(),
        b"zstd" => zstd::bulk::decompress(compressed, size)
            .map_err(|e| format!("a zstd chunk does not decompress: {e}"))?,
        other => {
            return Err(format!(
                "chunk compression {:?} is not supported (shroud writes zstd or none)",
                String::from_utf8_lossy(other)
            ))
        }
    };
    if content.len() != size {
        return Err(format!(
            "a chunk holds {} bytes where its header says {size}",
            content.len()
        ));
    }
    if crc != 0 && crc32fast::hash(&content) != crc {
        return Err("a chunk's CRC does not match its contents".into());
    }
    Ok(content)
}

/// The first `n` bytes and the rest.
fn take(data: &[u8], n: usize) -> Result<(&[u8], &[u8]), String> {
    if data.len() < n {
        return Err(format!(
            "a field of {n} bytes where {} are left in the chunk",
            data.len()
        ));
    }
    Ok(data.split_at(n))
}

fn take_u64(data: &[u8], n: u64) -> Result<(&[u8], &[u8]), String> {
    match usize::try_from(n) {
        Ok(n) => take(data, n),
        Err(_) => Err(format!("a field of {n} bytes")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A chunk record around `records` (uncompressed, CRC 0).
    fn chunk(records: &[u8], claimed: u64) -> Vec<u8> {
        let mut out = vec![0u8; 16];
        out.extend(claimed.to_le_bytes());
        out.extend(0u32.to_le_bytes());
        out.extend(0u32.to_le_bytes());
        out.extend((records.len() as u64).to_le_bytes());
        out.extend(records);
        out
    }

    fn record(opcode: u8, len: u64, data: &[u8]) -> Vec<u8> {
        let mut out = vec![opcode];
        out.extend(len.to_le_bytes());
        out.extend(data);
        out
    }

    fn walk(chunk: &[u8]) -> Result<Vec<u8>, String> {
        let mut seen = Vec::new();
        for_each_record(chunk, 1 << 20, |op, _| {
            seen.push(op);
            Ok::<_, String>(true)
        })?;
        Ok(seen)
    }

    #[test]
    fn records_are_walked_and_lengths_past_the_chunk_refused() {
        let records = [record(5, 3, b"abc"), record(7, 0, b"")].concat();
        assert_eq!(walk(&chunk(&records, records.len() as u64)), Ok(vec![5, 7]));
        let lying = record(5, 1000, b"abc");
        assert!(walk(&chunk(&lying, lying.len() as u64)).is_err());
        let huge = record(5, u64::MAX, b"abc");
        assert!(walk(&chunk(&huge, huge.len() as u64)).is_err());
        // The header's size must be the contents' size, and within the limit.
        assert!(walk(&chunk(&records, 3)).is_err());
        assert!(walk(&chunk(&records, u64::MAX)).is_err());
        assert!(walk(&[0u8; 20]).is_err());
    }
}
