//! The length-prefixed fields of the MCAP records shroud reads, checked to
//! fit inside their record before the `mcap` crate parses it: the crate
//! allocates what a string's length prefix claims (up to 4 GiB for a
//! 1.8 KB file, found by the `mcap_recording` fuzz target). Layouts from
//! the MCAP specification, "Records" (<https://mcap.dev/spec>).

use mcap::records::op;

/// One field of a record's layout.
#[derive(Clone, Copy)]
enum Field {
    /// A fixed number of bytes (integers).
    Fixed(usize),
    /// A u32 length, then that many bytes (a string, a schema's data).
    Prefixed,
    /// A u32 byte length, then `<string, string>` pairs within it.
    StringMap,
    /// A u32 byte length, then entries of this many bytes within it (the
    /// crate reads whole entries while short of the length: one that is
    /// not a multiple would shift every field after it).
    FixedMap(usize),
}

use Field::{Fixed, FixedMap, Prefixed, StringMap};

/// The records shroud's readers use and their layouts; other records are
/// skipped unparsed. A message's fixed header is followed by its data.
const LAYOUTS: [(u8, &[Field]); 6] = [
    (op::HEADER, &[Prefixed, Prefixed]),
    (op::SCHEMA, &[Fixed(2), Prefixed, Prefixed, Prefixed]),
    (op::CHANNEL, &[Fixed(4), Prefixed, Prefixed, StringMap]),
    (op::MESSAGE, &[Fixed(22)]),
    (op::METADATA, &[Prefixed, StringMap]),
    (
        op::CHUNK_INDEX,
        // message_index_offsets: u16 channel id -> u64 offset.
        &[Fixed(32), FixedMap(10), Fixed(8), Prefixed, Fixed(16)],
    ),
];

/// Whether records of `opcode` are parsed and handed out.
pub fn is_read(opcode: u8) -> bool {
    LAYOUTS.iter().any(|(o, _)| *o == opcode)
}

/// Checks that every field of a record of `opcode` fits in `data`.
pub fn check_fields(opcode: u8, data: &[u8]) -> Result<(), String> {
    let Some((_, layout)) = LAYOUTS.iter().find(|(o, _)| *o == opcode) else {
        return Ok(());
    };
    let mut rest = data;
    for field in *layout {
        rest = match field {
            Fixed(n) => take(rest, *n)?.1,
            Prefixed => prefixed(rest)?.1,
            FixedMap(entry) => {
                let (map, after) = prefixed(rest)?;
                if map.len() % entry != 0 {
                    return Err(format!(
                        "a map of {} bytes is not a whole number of {entry}-byte entries",
                        map.len()
                    ));
                }
                after
            }
            StringMap => {
                let (mut map, after) = prefixed(rest)?;
                while !map.is_empty() {
                    map = prefixed(prefixed(map)?.1)?.1;
                }
                after
            }
        };
    }
    Ok(())
}

/// The first `n` bytes and the rest.
fn take(data: &[u8], n: usize) -> Result<(&[u8], &[u8]), String> {
    if data.len() < n {
        return Err(format!(
            "a field of {n} bytes where the record has {} left",
            data.len()
        ));
    }
    Ok(data.split_at(n))
}

/// A u32-length-prefixed field and the rest.
fn prefixed(data: &[u8]) -> Result<(&[u8], &[u8]), String> {
    let (len, rest) = take(data, 4)?;
    let len = u32::from_le_bytes([len[0], len[1], len[2], len[3]]) as usize;
    take(rest, len)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn string(s: &str) -> Vec<u8> {
        let mut out = (s.len() as u32).to_le_bytes().to_vec();
        out.extend_from_slice(s.as_bytes());
        out
    }

    #[test]
    fn fields_that_fit_pass_and_lengths_past_the_record_are_refused() {
        let header = [string("p"), string("shroud")].concat();
        assert_eq!(check_fields(op::HEADER, &header), Ok(()));
        let mut lying = header.clone();
        lying[0..4].copy_from_slice(&u32::MAX.to_le_bytes());
        assert!(check_fields(op::HEADER, &lying).is_err());
        let map = [string("k"), string("v")].concat();
        let mut channel = vec![1, 0, 1, 0];
        channel.extend(string("shroud/a/cloud/b"));
        channel.extend(string("msgpack"));
        channel.extend((map.len() as u32).to_le_bytes());
        channel.extend(&map);
        assert_eq!(check_fields(op::CHANNEL, &channel), Ok(()));
        // A string inside the map claims 4 GiB.
        let at = channel.len() - map.len();
        channel[at..at + 4].copy_from_slice(&u32::MAX.to_le_bytes());
        assert!(check_fields(op::CHANNEL, &channel).is_err());
        assert!(check_fields(op::MESSAGE, &[0; 21]).is_err());
        // A chunk index whose offset map is not whole entries.
        let mut index = vec![0u8; 32];
        index.extend(5u32.to_le_bytes());
        index.extend([0u8; 5]);
        index.extend([0u8; 8]);
        index.extend(string("zstd"));
        index.extend([0u8; 16]);
        let e = check_fields(op::CHUNK_INDEX, &index).unwrap_err();
        assert!(e.contains("whole number"), "{e}");
        assert!(is_read(op::MESSAGE) && !is_read(op::STATISTICS));
    }
}
