//! MCAP recordings as `shroud mcap info` and `shroud replay` read them
//! (`shroud_record::read_records`): any bytes give records and an
//! ending, or a named error, within bounded memory; the first half of a
//! finished recording never yields more messages than the whole.

use crate::check::{bounded_allocation, named};
use shroud_msg::{TopicKey, TopicKind};
use shroud_record::layout::{channel_metadata, schema_for, MESSAGE_ENCODING};
use shroud_record::{read_records, Ending};

pub fn run(data: &[u8]) {
    bounded_allocation(data.len(), || {
        let Some((whole, Ending::Complete)) = messages(data) else {
            return;
        };
        if let Some((half, _)) = messages(&data[..data.len() / 2]) {
            assert!(half <= whole, "a prefix gave {half} messages, the whole {whole}");
        }
    });
}

/// The messages read and the ending; `None` after a (named) error.
fn messages(data: &[u8]) -> Option<(u64, Ending)> {
    let mut n = 0u64;
    let read = read_records(data, data.len() as u64, |record| {
        n += u64::from(matches!(record, mcap::records::Record::Message { .. }));
        true
    });
    match read {
        Ok(ending) => Some((n, ending)),
        Err(e) => {
            named(&e);
            None
        }
    }
}

pub fn seeds() -> Vec<Vec<u8>> {
    [None, Some(mcap::Compression::Zstd)]
        .into_iter()
        .map(recording)
        .collect()
}

/// A small recording laid out as `shroud record` lays one out: a cloud and
/// a status channel, three messages each, in chunks of about 200 bytes.
fn recording(compression: Option<mcap::Compression>) -> Vec<u8> {
    let mut out = std::io::Cursor::new(Vec::new());
    let mut writer = mcap::WriteOptions::new()
        .compression(compression)
        .chunk_size(Some(200))
        .create(&mut out)
        .expect("an MCAP writer");
    for (kind, name) in [(TopicKind::Cloud, "front"), (TopicKind::Status, "fit")] {
        let key = TopicKey {
            namespace: "demo".into(),
            kind,
            name: name.into(),
        };
        let schema = schema_for(kind);
        let schema_id = writer
            .add_schema(&schema.name, schema.encoding, &schema.data)
            .expect("a schema");
        let topic = format!("shroud/demo/{kind}/{name}");
        let channel = writer
            .add_channel(schema_id, &topic, MESSAGE_ENCODING, &channel_metadata(&key))
            .expect("a channel");
        for i in 0..3u32 {
            let header = mcap::records::MessageHeader {
                channel_id: channel,
                sequence: i,
                log_time: u64::from(i) * 1_000_000,
                publish_time: u64::from(i) * 1_000_000,
            };
            writer
                .write_to_known_channel(&header, &[i as u8; 64])
                .expect("a message");
        }
    }
    writer.finish().expect("a finished recording");
    drop(writer);
    out.into_inner()
}
