//! One MCAP file being written: the `mcap` crate's writer over a buffered
//! file, shroud's schemas and channels (`shroud-record`'s [`layout`]) and those of the
//! Foxglove views added on first use,
//! a sequence per channel, and the bytes and messages written so far; with
//! `--ros2`, also the ROS 2 file beside it (`<stem>.ros2.mcap`: CDR channels
//! with `ros2msg` schemas only, which rosbags and `ros2 bag play` read).

use super::views::View;
use anyhow::{Context, Result};
use shroud_msg::{TopicKey, TopicKind};
use shroud_record::layout::{self, MESSAGE_ENCODING, RECORDING_METADATA};
use shroud_record::ros2::{
    ros2_path, RosChannel, ROS2_MESSAGE_ENCODING, ROS2_PROFILE, ROS2_SCHEMA_ENCODING,
};
use std::collections::{BTreeMap, HashMap};
use std::fs::File;
use std::io::{BufWriter, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

/// A message to store: its topic, the times of the MCAP message header, its
/// payload as it travelled.
pub struct StoredMessage<'a> {
    pub key: &'a TopicKey,
    pub topic: &'a str,
    pub log_ns: u64,
    pub publish_ns: u64,
    pub payload: &'a [u8],
}

/// How the file is compressed and described.
#[derive(Debug, Clone)]
pub struct FileOptions {
    pub compression: Option<mcap::Compression>,
    /// The `shroud.recording` metadata record.
    pub metadata: BTreeMap<String, String>,
    /// Replace existing files (else an existing file is an error).
    pub overwrite: bool,
    /// Also write the ROS 2 file beside each file (`--ros2`).
    pub ros2: bool,
}

pub struct McapFile {
    path: PathBuf,
    writer: mcap::Writer<Sink>,
    schemas: HashMap<TopicKind, u16>,
    /// The Foxglove schemas of `--foxglove` views, by name.
    view_schemas: HashMap<String, u16>,
    channels: HashMap<String, (u16, u32)>,
    messages: u64,
    /// The sink's byte count (`mcap::Writer` does not lend its sink).
    len: Arc<AtomicU64>,
    ros2: Option<Ros2File>,
}

type Sink = Counting<BufWriter<File>>;

/// The ROS 2 file beside the recording's (`--ros2`): its channels by topic
/// with their next sequence, and its byte count.
struct Ros2File {
    path: PathBuf,
    writer: mcap::Writer<Sink>,
    channels: HashMap<String, (u16, u32)>,
    len: Arc<AtomicU64>,
}

/// Writes a message of `channel_id` (its `sequence`) at `(log, publish)`
/// times into `path`'s writer.
fn put(
    writer: &mut mcap::Writer<Sink>,
    path: &Path,
    (channel_id, sequence): (u16, u32),
    (log_time, publish_time): (u64, u64),
    data: &[u8],
) -> Result<()> {
    let header = mcap::records::MessageHeader {
        channel_id,
        sequence,
        log_time,
        publish_time,
    };
    writer
        .write_to_known_channel(&header, data)
        .with_context(|| format!("cannot write to {}", path.display()))
}

/// Creates `path` (refusing an existing file unless `overwrite`) and starts
/// an MCAP writer of `profile` on it.
fn start_file(
    path: &Path,
    options: &FileOptions,
    profile: &str,
) -> Result<(mcap::Writer<Sink>, Arc<AtomicU64>)> {
    // A split file that exists is not replaced either (`--overwrite`).
    let file = std::fs::OpenOptions::new()
        .write(true)
        .create(true)
        .truncate(true)
        .create_new(!options.overwrite)
        .open(path)
        .map_err(|e| match e.kind() {
            std::io::ErrorKind::AlreadyExists => {
                anyhow::anyhow!("{} exists (give --overwrite to replace it)", path.display())
            }
            _ => anyhow::Error::new(e).context(format!("cannot create {}", path.display())),
        })?;
    let (sink, len) = Counting::new(BufWriter::with_capacity(1 << 20, file));
    // Chunks are closed by the recorder (`ChunkPolicy`), never by size
    // inside the crate, so that free space is checked before each one.
    // Each chunk is built in memory and written whole: when seeking, the
    // crate streams a chunk behind a placeholder header that it patches
    // at the chunk's end, and a recorder killed mid-chunk would leave a
    // header whose lengths lie (the reader then fails on it) instead of
    // a file that merely stops early.
    let writer = mcap::WriteOptions::new()
        .compression(options.compression)
        .chunk_size(None)
        .disable_seeking(true)
        .profile(profile)
        .library(format!("shroud {}", env!("CARGO_PKG_VERSION")))
        .create(sink)
        .with_context(|| format!("cannot start {}", path.display()))?;
    Ok((writer, len))
}

impl McapFile {
    pub fn create(path: &Path, options: &FileOptions) -> Result<Self> {
        let (mut writer, len) = start_file(path, options, "")?;
        let ros2 = match options.ros2 {
            true => {
                let ros_path = ros2_path(path);
                let (writer, len) = start_file(&ros_path, options, ROS2_PROFILE)?;
                Some(Ros2File {
                    path: ros_path,
                    writer,
                    channels: HashMap::new(),
                    len,
                })
            }
            false => None,
        };
        writer
            .write_metadata(&mcap::records::Metadata {
                name: RECORDING_METADATA.to_owned(),
                metadata: options.metadata.clone(),
            })
            .with_context(|| format!("cannot write to {}", path.display()))?;
        Ok(Self {
            path: path.to_path_buf(),
            writer,
            schemas: HashMap::new(),
            view_schemas: HashMap::new(),
            channels: HashMap::new(),
            messages: 0,
            len,
            ros2,
        })
    }

    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Bytes handed to the file (and its ROS 2 file) so far (buffered or
    /// written).
    pub fn bytes(&self) -> u64 {
        let ros2 = self
            .ros2
            .as_ref()
            .map_or(0, |r| r.len.load(Ordering::Relaxed));
        self.len.load(Ordering::Relaxed) + ros2
    }

    /// The ROS 2 file beside this one, if any.
    pub fn ros2_path(&self) -> Option<&Path> {
        self.ros2.as_ref().map(|r| r.path.as_path())
    }

    /// Writes a ROS 2 message (CDR) into the ROS 2 file; nothing without one.
    pub fn write_ros2(
        &mut self,
        channel: &RosChannel,
        log_ns: u64,
        publish_ns: u64,
        cdr: &[u8],
    ) -> Result<()> {
        let Some(ros) = self.ros2.as_mut() else {
            return Ok(());
        };
        let path = &ros.path;
        let (channel_id, sequence) = match ros.channels.get_mut(&channel.topic) {
            Some((id, sequence)) => {
                *sequence = sequence.wrapping_add(1);
                (*id, *sequence)
            }
            None => {
                let schema = ros
                    .writer
                    .add_schema(
                        channel.type_name,
                        ROS2_SCHEMA_ENCODING,
                        channel.definition().as_bytes(),
                    )
                    .with_context(|| format!("cannot write to {}", path.display()))?;
                let id = ros
                    .writer
                    .add_channel(
                        schema,
                        &channel.topic,
                        ROS2_MESSAGE_ENCODING,
                        &BTreeMap::new(),
                    )
                    .with_context(|| format!("cannot write to {}", path.display()))?;
                ros.channels.insert(channel.topic.clone(), (id, 0));
                (id, 0)
            }
        };
        put(
            &mut ros.writer,
            path,
            (channel_id, sequence),
            (log_ns, publish_ns),
            cdr,
        )
    }

    pub fn messages(&self) -> u64 {
        self.messages
    }

    pub fn write(&mut self, message: &StoredMessage<'_>) -> Result<()> {
        let (channel_id, sequence) = self.channel(message.key, message.topic)?;
        put(
            &mut self.writer,
            &self.path,
            (channel_id, sequence),
            (message.log_ns, message.publish_ns),
            message.payload,
        )?;
        self.messages += 1;
        Ok(())
    }

    /// Closes the open chunk and flushes it to the file.
    pub fn close_chunk(&mut self) -> Result<()> {
        if let Some(ros) = self.ros2.as_mut() {
            ros.writer
                .flush()
                .with_context(|| format!("cannot write to {}", ros.path.display()))?;
        }
        self.writer
            .flush()
            .with_context(|| format!("cannot write to {}", self.path.display()))
    }

    /// Writes the summary and footer (of both files with `--ros2`): the file
    /// is complete. Its bytes (with the ROS 2 file's).
    pub fn finish(mut self) -> Result<u64> {
        let ros = match self.ros2.as_mut() {
            Some(ros) => ros
                .writer
                .finish()
                .map(drop)
                .with_context(|| format!("cannot finish {}", ros.path.display())),
            None => Ok(()),
        };
        self.writer
            .finish()
            .with_context(|| format!("cannot finish {}", self.path.display()))?;
        ros?;
        Ok(self.bytes())
    }

    /// The channel of shroud's `topic` and its next sequence number.
    fn channel(&mut self, key: &TopicKey, topic: &str) -> Result<(u16, u32)> {
        if let Some(next) = self.next_in(topic) {
            return Ok(next);
        }
        let schema_id = match self.schemas.get(&key.kind) {
            Some(&id) => id,
            None => {
                let schema = layout::schema_for(key.kind);
                let id = self.add_schema(&schema.name, schema.encoding, &schema.data)?;
                self.schemas.insert(key.kind, id);
                id
            }
        };
        self.add_channel(
            schema_id,
            topic,
            MESSAGE_ENCODING,
            &layout::channel_metadata(key),
        )
    }

    /// Writes a Foxglove view of a recorded message (`--foxglove`), on its
    /// own channel with the schema the `foxglove` crate declares.
    pub fn write_view(&mut self, view: &View, log_ns: u64, publish_ns: u64) -> Result<()> {
        let (channel_id, sequence) = match self.next_in(&view.topic) {
            Some(next) => next,
            None => {
                let s = view
                    .schema()
                    .with_context(|| format!("{}: no schema to record", view.topic))?;
                let schema_id = match self.view_schemas.get(&s.name) {
                    Some(&id) => id,
                    None => {
                        let id = self.add_schema(&s.name, &s.encoding, &s.data)?;
                        self.view_schemas.insert(s.name.clone(), id);
                        id
                    }
                };
                let encoding = view.message_encoding.clone();
                self.add_channel(schema_id, &view.topic, &encoding, &BTreeMap::new())?
            }
        };
        put(
            &mut self.writer,
            &self.path,
            (channel_id, sequence),
            (log_ns, publish_ns),
            &view.data,
        )?;
        self.messages += 1;
        Ok(())
    }

    /// The next sequence number of a known channel.
    fn next_in(&mut self, topic: &str) -> Option<(u16, u32)> {
        let (id, sequence) = self.channels.get_mut(topic)?;
        *sequence = sequence.wrapping_add(1);
        Some((*id, *sequence))
    }

    fn add_schema(&mut self, name: &str, encoding: &str, data: &[u8]) -> Result<u16> {
        self.writer
            .add_schema(name, encoding, data)
            .with_context(|| format!("cannot write to {}", self.path.display()))
    }

    fn add_channel(
        &mut self,
        schema_id: u16,
        topic: &str,
        encoding: &str,
        metadata: &BTreeMap<String, String>,
    ) -> Result<(u16, u32)> {
        let id = self
            .writer
            .add_channel(schema_id, topic, encoding, metadata)
            .with_context(|| format!("cannot write to {}", self.path.display()))?;
        self.channels.insert(topic.to_owned(), (id, 0));
        Ok((id, 0))
    }
}

/// A sink that counts the bytes of the file (its furthest position).
pub struct Counting<W> {
    inner: W,
    position: u64,
    len: Arc<AtomicU64>,
}

impl<W> Counting<W> {
    fn new(inner: W) -> (Self, Arc<AtomicU64>) {
        let len = Arc::new(AtomicU64::new(0));
        let sink = Self {
            inner,
            position: 0,
            len: len.clone(),
        };
        (sink, len)
    }
}

impl<W: Write> Write for Counting<W> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let n = self.inner.write(buf)?;
        self.position += n as u64;
        self.len.fetch_max(self.position, Ordering::Relaxed);
        Ok(n)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.inner.flush()
    }
}

impl<W: Seek> Seek for Counting<W> {
    fn seek(&mut self, pos: SeekFrom) -> std::io::Result<u64> {
        self.position = self.inner.seek(pos)?;
        Ok(self.position)
    }
}
