//! The recorder's writer thread: takes arrivals off the queue and writes them
//! to the MCAP file, closing chunks by `shroud-record`'s [`ChunkPolicy`], checking free
//! space (statvfs) before each chunk against the [`DiskReserve`], starting a
//! new file by the [`SplitPolicy`], and ending the file whatever happens: on
//! a full disk it stops taking messages (they are counted as drops) and
//! finishes the file cleanly; on a write error it stops too and tries to
//! finish it (a disk that refuses leaves it truncated, still readable).

use super::disk::free_bytes;
use super::mcap_file::{FileOptions, McapFile, StoredMessage};
use super::ros2_out::ros2_message;
use super::shared::Recording;
use super::views::FoxgloveViews;
use crate::transport::{unix_ns, WaitQueue};
use anyhow::Result;
use shroud_msg::TopicKey;
use shroud_record::{split_path, ByteQueue, ChunkPolicy, DiskReserve, DropCause, SplitPolicy};
use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};
use zenoh::bytes::ZBytes;

/// A message as the subscriber received it.
pub struct Arrival {
    pub key: TopicKey,
    pub topic: String,
    pub payload: ZBytes,
    pub log_ns: u64,
    pub publish_ns: u64,
}

/// Where and how the recording is written.
pub struct WriterPlan {
    pub base: PathBuf,
    pub split: SplitPolicy,
    pub chunk: ChunkPolicy,
    pub reserve: DiskReserve,
    pub options: FileOptions,
    /// The Foxglove views written beside the raw messages (`--foxglove`).
    pub views: Option<FoxgloveViews>,
}

/// A file of the recording once finished.
#[derive(Debug, Clone)]
pub struct WrittenFile {
    pub path: PathBuf,
    /// Its ROS 2 file (`--ros2`).
    pub ros2: Option<PathBuf>,
    /// Bytes of both files.
    pub bytes: u64,
    pub messages: u64,
}

/// How often the writer looks at the chunk's age while no message comes.
const IDLE_POLL: Duration = Duration::from_millis(100);

struct Writer {
    plan: WriterPlan,
    file: Option<McapFile>,
    index: u32,
    chunk_bytes: u64,
    chunk_started: Instant,
    written: Vec<WrittenFile>,
    recording: Arc<Recording>,
}

/// Writes until the queue is closed and drained; returns the files written.
/// `first` is the recording's first file, already created (so that a bad
/// path fails before the node starts).
pub fn run_writer(
    plan: WriterPlan,
    first: McapFile,
    queue: Arc<WaitQueue<ByteQueue<Arrival>>>,
    recording: Arc<Recording>,
) -> Vec<WrittenFile> {
    let mut writer = Writer {
        plan,
        file: Some(first),
        index: 0,
        chunk_bytes: 0,
        chunk_started: Instant::now(),
        written: Vec::new(),
        recording,
    };
    loop {
        match queue.take(IDLE_POLL) {
            Some(arrival) => writer.take(arrival),
            None if queue.is_drained() => break,
            None => writer.write_periodic_views(unix_ns()),
        }
        writer.close_chunk_if_due();
        writer.recording.queue_bytes(queue.read(|q| q.bytes()));
    }
    writer.finish_file();
    writer.written
}

impl Writer {
    fn take(&mut self, arrival: Arrival) {
        if let Some(cause) = self.recording.refusing() {
            self.recording.dropped(&arrival.topic, cause);
            return;
        }
        let payload = arrival.payload.to_bytes();
        if let Err(e) = self.write(&arrival, &payload) {
            tracing::error!("recording stopped: {e:#}");
            self.recording
                .dropped(&arrival.topic, DropCause::WriteError);
            self.recording
                .refuse(DropCause::WriteError, format!("{e:#}"));
            self.finish_file();
        }
    }

    fn write(&mut self, arrival: &Arrival, payload: &[u8]) -> Result<()> {
        let len = payload.len() as u64;
        let (bytes, messages) = self
            .file
            .as_ref()
            .map_or((0, 0), |f| (f.bytes(), f.messages()));
        // The open chunk is still in memory: it counts toward the file.
        if self
            .plan
            .split
            .should_split(bytes + self.chunk_bytes, messages, len)
        {
            self.finish_file();
            self.index += 1;
            let path = split_path(&self.plan.base, true, self.index);
            self.file = Some(McapFile::create(&path, &self.plan.options)?);
            tracing::info!(path = %path.display(), "next file");
        }
        if self.chunk_bytes == 0 && !self.disk_admits_chunk() {
            self.recording.dropped(&arrival.topic, DropCause::DiskFull);
            return Ok(());
        }
        let Some(file) = self.file.as_mut() else {
            self.recording
                .dropped(&arrival.topic, DropCause::WriteError);
            return Ok(());
        };
        file.write(&StoredMessage {
            key: &arrival.key,
            topic: &arrival.topic,
            log_ns: arrival.log_ns,
            publish_ns: arrival.publish_ns,
            payload,
        })?;
        let message = Some((&arrival.key, payload));
        let views = self.write_views(message, arrival.log_ns, arrival.publish_ns)?;
        let ros2 = self.write_ros2(arrival, payload)?;
        self.recording.written(len);
        self.add_to_chunk(len + views + ros2);
        Ok(())
    }

    /// Writes the ROS 2 message of a message just written (`--ros2`),
    /// returning its bytes; one that does not convert is counted and logged
    /// (its raw record stays).
    fn write_ros2(&mut self, arrival: &Arrival, payload: &[u8]) -> Result<u64> {
        let Some(file) = self.file.as_mut().filter(|f| f.ros2_path().is_some()) else {
            return Ok(0);
        };
        match ros2_message(&arrival.key, payload) {
            None => Ok(0),
            Some(Err(e)) => {
                self.recording.ros2_failed(&e);
                Ok(0)
            }
            Some(Ok((channel, cdr))) => {
                file.write_ros2(&channel, arrival.log_ns, arrival.publish_ns, &cdr)?;
                Ok(cdr.len() as u64)
            }
        }
    }

    /// Bytes just written into the open chunk (which starts its age with
    /// its first record).
    fn add_to_chunk(&mut self, bytes: u64) {
        if bytes == 0 {
            return;
        }
        if self.chunk_bytes == 0 {
            self.chunk_started = Instant::now();
        }
        self.chunk_bytes += bytes;
    }

    /// Writes the verdict views due at `log_ns` and the Foxglove views of
    /// `message` (a message just written), returning their bytes. A message
    /// that does not convert is counted and logged (`views_failed`): its raw
    /// record stays, and the verdicts due are written all the same.
    fn write_views(
        &mut self,
        message: Option<(&TopicKey, &[u8])>,
        log_ns: u64,
        publish_ns: u64,
    ) -> Result<u64> {
        let (Some(views), Some(file)) = (self.plan.views.as_mut(), self.file.as_mut()) else {
            return Ok(0);
        };
        let mut made = Vec::new();
        let of_message = message.map(|(key, payload)| views.of_message(key, payload, log_ns));
        for result in [Some(views.periodic(log_ns)), of_message]
            .into_iter()
            .flatten()
        {
            match result {
                Ok(more) => made.extend(more),
                Err(e) => self.recording.view_failed(&e),
            }
        }
        let mut bytes = 0;
        for view in &made {
            file.write_view(view, log_ns, publish_ns)?;
            bytes += view.data.len() as u64;
        }
        self.recording
            .views_written(made.len() as u64, views.paced());
        Ok(bytes)
    }

    /// While no message comes, the verdicts still go out every 100 ms (a
    /// silent guard shows as `no-verdict` in the recording), into chunks
    /// that close and are checked against the disk as any other.
    fn write_periodic_views(&mut self, now_ns: u64) {
        let due = self
            .plan
            .views
            .as_ref()
            .is_some_and(|v| v.verdicts_due(now_ns));
        if !due || self.file.is_none() {
            return;
        }
        if self.chunk_bytes == 0 && !self.disk_admits_chunk() {
            return;
        }
        match self.write_views(None, now_ns, now_ns) {
            Ok(bytes) => self.add_to_chunk(bytes),
            Err(e) => {
                tracing::error!("recording stopped: {e:#}");
                self.recording
                    .refuse(DropCause::WriteError, format!("{e:#}"));
                self.finish_file();
            }
        }
    }

    /// Before a chunk starts: is there room for it and the reserve? If not,
    /// the recording stops and the file is finished.
    fn disk_admits_chunk(&mut self) -> bool {
        let dir = self
            .plan
            .base
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(std::path::Path::new("."));
        let Some(free) = free_bytes(dir) else {
            return true;
        };
        if self.plan.reserve.admits(free, self.plan.chunk.chunk_bytes) {
            return true;
        }
        let reason = format!(
            "{:.0} MB free on the disk of {}, less than the reserve ({:.0} MB) and a chunk",
            free as f64 / 1e6,
            dir.display(),
            self.plan.reserve.reserve_bytes as f64 / 1e6
        );
        tracing::error!("recording stopped: {reason}");
        self.recording.refuse(DropCause::DiskFull, reason);
        self.finish_file();
        false
    }

    fn close_chunk_if_due(&mut self) {
        let age = self.chunk_started.elapsed().as_nanos() as u64;
        if !self.plan.chunk.should_close(self.chunk_bytes, age) {
            return;
        }
        self.chunk_bytes = 0;
        if let Some(file) = self.file.as_mut() {
            if let Err(e) = file.close_chunk() {
                tracing::error!("recording stopped: {e:#}");
                self.recording
                    .refuse(DropCause::WriteError, format!("{e:#}"));
                self.finish_file();
            }
        }
    }

    /// Finishes the open file (summary, footer); a file that cannot be
    /// finished is reported, and left as a truncated file that
    /// `shroud mcap info` can still read.
    fn finish_file(&mut self) {
        self.chunk_bytes = 0;
        let Some(file) = self.file.take() else {
            return;
        };
        let (path, messages) = (file.path().to_path_buf(), file.messages());
        let ros2 = file.ros2_path().map(std::path::Path::to_path_buf);
        match file.finish() {
            Ok(bytes) => self.written.push(WrittenFile {
                path,
                ros2,
                bytes,
                messages,
            }),
            Err(e) => {
                tracing::error!("{e:#}");
                self.recording
                    .refuse(DropCause::WriteError, format!("{e:#}"));
            }
        }
    }
}
