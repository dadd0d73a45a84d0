//! `shroud mcap info FILE`: what an MCAP file holds (channels with their
//! encodings, schemas and counts; messages, duration, start and end; size;
//! chunk compression), read to the end rather than from its index, so that a
//! truncated file is reported with what it still holds. Exit status: 0 for a
//! complete file, 3 for a truncated one (the report is printed first), 1 for
//! an empty, foreign or corrupt file.

use super::reader::{read_records, Ending};
use crate::exit::ExitWith;
use anyhow::{Context, Result};
use clap::Args;
use mcap::records::Record;
use std::collections::BTreeMap;
use std::path::PathBuf;

/// The exit status of `shroud mcap info` for a truncated file.
pub const TRUNCATED_EXIT: u8 = 3;

#[derive(Debug, Clone, Args)]
pub struct InfoArgs {
    /// The MCAP file.
    pub file: PathBuf,
}

#[derive(Default)]
struct Channel {
    topic: String,
    message_encoding: String,
    schema_id: u16,
    messages: u64,
}

#[derive(Default)]
struct Compression {
    chunks: u64,
    compressed: u64,
    uncompressed: u64,
}

/// What a pass over the file found.
#[derive(Default)]
struct Contents {
    library: String,
    profile: String,
    schemas: BTreeMap<u16, (String, String)>,
    channels: BTreeMap<u16, Channel>,
    messages: u64,
    first_ns: Option<u64>,
    last_ns: u64,
    compression: BTreeMap<String, Compression>,
    metadata: Vec<(String, BTreeMap<String, String>)>,
}

impl Contents {
    fn take(&mut self, record: Record<'_>) {
        match record {
            Record::Header(h) => {
                self.library = h.library;
                self.profile = h.profile;
            }
            Record::Schema { header, .. } => {
                self.schemas
                    .insert(header.id, (header.name, header.encoding));
            }
            // The summary repeats the channels: the first record counts.
            Record::Channel(c) => {
                self.channels.entry(c.id).or_insert(Channel {
                    topic: c.topic,
                    message_encoding: c.message_encoding,
                    schema_id: c.schema_id,
                    messages: 0,
                });
            }
            Record::Message { header, .. } => {
                self.messages += 1;
                self.first_ns = Some(
                    self.first_ns
                        .map_or(header.log_time, |f| f.min(header.log_time)),
                );
                self.last_ns = self.last_ns.max(header.log_time);
                if let Some(c) = self.channels.get_mut(&header.channel_id) {
                    c.messages += 1;
                }
            }
            Record::ChunkIndex(i) => {
                let entry = self.compression.entry(i.compression).or_default();
                // Sizes from the file: a corrupt index must not overflow.
                entry.chunks += 1;
                entry.compressed = entry.compressed.saturating_add(i.compressed_size);
                entry.uncompressed = entry.uncompressed.saturating_add(i.uncompressed_size);
            }
            Record::Metadata(m) => self.metadata.push((m.name, m.metadata)),
            _ => {}
        }
    }
}

pub fn run(args: &InfoArgs) -> Result<()> {
    let size = std::fs::metadata(&args.file)
        .with_context(|| format!("cannot open {}", args.file.display()))?
        .len();
    let mut contents = Contents::default();
    let ending = read_records(&args.file, |record| {
        contents.take(record);
        Ok(true)
    })?;
    print_report(&args.file, size, &contents, &ending);
    match ending {
        Ending::Complete => Ok(()),
        Ending::Truncated { reason, .. } => Err(ExitWith::new(
            TRUNCATED_EXIT,
            format!(
                "{} is truncated ({reason}); {} messages of its complete chunks are readable",
                args.file.display(),
                contents.messages
            ),
        )
        .into()),
    }
}

fn print_report(file: &std::path::Path, size: u64, c: &Contents, ending: &Ending) {
    println!("file:        {}", file.display());
    println!("size:        {}", megabytes(size));
    match ending {
        Ending::Complete => println!("state:       complete"),
        Ending::Truncated { reason, .. } => println!(
            "state:       TRUNCATED ({reason}); recovered {} messages from complete chunks",
            c.messages
        ),
    }
    println!("library:     {}", c.library);
    println!("profile:     {}", c.profile);
    println!("messages:    {}", c.messages);
    let (first, last) = (c.first_ns.unwrap_or(0), c.last_ns);
    let duration = last.saturating_sub(first) as f64 / 1e9;
    println!("duration:    {duration:.3} s");
    println!(
        "start:       {} (log time, s since the Unix epoch)",
        seconds(first)
    );
    println!("end:         {}", seconds(last));
    if c.compression.is_empty() {
        println!("compression: unknown (no chunk index: the file was not finished)");
    }
    for (name, z) in &c.compression {
        let name = if name.is_empty() { "none" } else { name };
        println!(
            "compression: {name}: {} chunks, {} -> {} ({:.0} %)",
            z.chunks,
            megabytes(z.uncompressed),
            megabytes(z.compressed),
            100.0 * z.compressed as f64 / z.uncompressed.max(1) as f64
        );
    }
    for (name, _) in &c.metadata {
        println!("metadata:    {name}");
    }
    println!("channels:");
    for (id, ch) in &c.channels {
        let (schema, encoding) = c
            .schemas
            .get(&ch.schema_id)
            .map(|(n, e)| (n.as_str(), e.as_str()))
            .unwrap_or(("(none)", ""));
        let rate = match duration > 0.0 {
            true => format!("{:.2} Hz", ch.messages as f64 / duration),
            false => "-".into(),
        };
        println!(
            "  ({id}) {}  {} msgs ({rate})  {}  {schema} [{encoding}]",
            ch.topic, ch.messages, ch.message_encoding
        );
    }
}

fn megabytes(bytes: u64) -> String {
    format!("{:.3} MB", bytes as f64 / 1e6)
}

fn seconds(ns: u64) -> String {
    format!("{}.{:09}", ns / 1_000_000_000, ns % 1_000_000_000)
}
