//! Named per-point channels of a cloud beyond xyz and intensity (a radar's
//! velocities, RCS, dynamic property): one little-endian f32 blob per name,
//! checked against the cloud's point count. Consumers that do not know a
//! channel ignore it.

use super::error::MessageError;
use serde_bytes::ByteBuf;
use std::collections::BTreeMap;

/// At most this many channels in one cloud.
pub const MAX_CHANNELS: usize = 16;
/// At most this many bytes in a channel's name.
pub const MAX_CHANNEL_NAME: usize = 32;

/// The wire form: channel name to `N x 4` bytes of little-endian f32.
pub type ChannelBlobs = BTreeMap<String, ByteBuf>;

/// One channel: a value per point, in the points' order.
#[derive(Debug, Clone, PartialEq)]
pub struct PointChannel {
    pub name: String,
    pub values: Vec<f32>,
}

impl PointChannel {
    pub fn new(name: &str, values: Vec<f32>) -> Self {
        Self {
            name: name.to_owned(),
            values,
        }
    }
}

/// Channels as their wire blobs (`None` when there are none).
pub fn channels_to_blobs(channels: &[PointChannel]) -> Option<ChannelBlobs> {
    if channels.is_empty() {
        return None;
    }
    let blobs = channels.iter().map(|c| {
        let bytes: Vec<u8> = c.values.iter().flat_map(|v| v.to_le_bytes()).collect();
        (c.name.clone(), ByteBuf::from(bytes))
    });
    Some(blobs.collect())
}

/// Checks names and lengths: at most [`MAX_CHANNELS`] channels, each named
/// in lower-case ASCII letters, digits and `_` (at most [`MAX_CHANNEL_NAME`]
/// bytes), each holding exactly `points` values. Values may be NaN (a
/// channel's "not measured").
pub fn check_channels(blobs: &ChannelBlobs, points: usize) -> Result<(), MessageError> {
    if blobs.len() > MAX_CHANNELS {
        return Err(MessageError::Invalid {
            field: "channels",
            reason: format!("{} channels, at most {MAX_CHANNELS}", blobs.len()),
        });
    }
    for (name, blob) in blobs {
        let well_named = !name.is_empty()
            && name.len() <= MAX_CHANNEL_NAME
            && name
                .bytes()
                .all(|b| b.is_ascii_lowercase() || b.is_ascii_digit() || b == b'_');
        if !well_named {
            return Err(MessageError::Invalid {
                field: "channels",
                reason: format!(
                    "channel name {name:?}: use 1 to {MAX_CHANNEL_NAME} of a-z, 0-9, _"
                ),
            });
        }
        if blob.len() != 4 * points {
            return Err(MessageError::Count {
                field: "channels",
                found: blob.len() / 4,
                expected: points,
            });
        }
    }
    Ok(())
}

/// Checks channels before they are sent: distinct names, and what
/// [`check_channels`] checks of the wire form (a producer's mistake is its
/// own error, not a cloud every consumer refuses).
pub fn check_point_channels(channels: &[PointChannel], points: usize) -> Result<(), MessageError> {
    let mut names: Vec<&str> = channels.iter().map(|c| c.name.as_str()).collect();
    names.sort_unstable();
    if let Some(twice) = names.windows(2).find(|w| w[0] == w[1]) {
        return Err(MessageError::Invalid {
            field: "channels",
            reason: format!("channel {:?} given twice", twice[0]),
        });
    }
    match channels_to_blobs(channels) {
        Some(blobs) => check_channels(&blobs, points),
        None => Ok(()),
    }
}

/// The channels as values (after [`check_channels`]).
pub fn blobs_to_channels(blobs: &ChannelBlobs) -> Vec<PointChannel> {
    blobs
        .iter()
        .map(|(name, blob)| PointChannel {
            name: name.clone(),
            values: blob
                .chunks_exact(4)
                .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
                .collect(),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn channels_round_trip_and_are_checked() {
        let channels = vec![
            PointChannel::new("rcs", vec![5.0, -3.5]),
            PointChannel::new("velocity_long", vec![0.25, f32::NAN]),
        ];
        let blobs = channels_to_blobs(&channels).unwrap();
        assert_eq!(&blobs["rcs"][..4], &5.0f32.to_le_bytes());
        check_channels(&blobs, 2).unwrap();
        let back = blobs_to_channels(&blobs);
        assert_eq!(back[0], channels[0]);
        assert!(back[1].values[1].is_nan());
        assert!(matches!(
            check_channels(&blobs, 3),
            Err(MessageError::Count { .. })
        ));
        for bad in ["", "RCS", "a b", &"x".repeat(33)] {
            let mut named = ChannelBlobs::new();
            named.insert(bad.to_owned(), ByteBuf::from(vec![0; 8]));
            assert!(check_channels(&named, 2).is_err(), "{bad:?}");
        }
        let many: ChannelBlobs = (0..=MAX_CHANNELS)
            .map(|i| (format!("c{i}"), ByteBuf::new()))
            .collect();
        assert!(check_channels(&many, 0).is_err());
        assert_eq!(channels_to_blobs(&[]), None);
        check_point_channels(&channels, 2).unwrap();
        let twice = [channels[0].clone(), channels[0].clone()];
        assert!(check_point_channels(&twice, 2).is_err());
        assert!(check_point_channels(&channels, 3).is_err());
    }
}
