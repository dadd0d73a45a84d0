//! Point-cloud messages: stamp, sequence, source, sensor pose, and the points as
//! raw little-endian f32 xyz (12 bytes a point) with optional f32 intensity.

use super::blob::{bytes_to_f32s, encode, f32s_to_bytes};
use super::channels::{
    blobs_to_channels, channels_to_blobs, check_channels, ChannelBlobs, PointChannel,
};
use super::error::MessageError;
use super::SCHEMA_VERSION;
use super::{FieldOfView, NoReturn};
use serde::{Deserialize, Serialize};

/// Sensor pose in the world: position and unit quaternion `[x, y, z, w]`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SensorPose {
    pub position: [f64; 3],
    pub orientation: [f64; 4],
}

impl Default for SensorPose {
    fn default() -> Self {
        Self {
            position: [0.0; 3],
            orientation: [0.0, 0.0, 0.0, 1.0],
        }
    }
}

/// A point cloud on the wire (MessagePack map with these field names).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CloudMessage {
    pub version: u16,
    /// Acquisition time, nanoseconds since the Unix epoch.
    pub stamp_ns: u64,
    pub sequence: u64,
    /// Time the cloud has spent in shroud nodes before this publication, each
    /// node measuring its own share on its own monotonic clock: from the first
    /// node's receipt of the data (the last byte of a scan, or the simulator's
    /// output) to this publication's encoding. Unlike `stamp_ns`, which is the device's
    /// word, this is what safety decisions age clouds by.
    pub pipeline_ns: u64,
    /// The largest distance, in metres, between a point of this cloud and
    /// where the sensor really measured it, as far as the producer can
    /// bound it: a reading of a sensor without its own clock, read late by
    /// a loaded host, is placed at an uncertain mount angle (finite, >= 0;
    /// 0 when nothing is known to add, and in messages from before the
    /// field existed).
    #[serde(default)]
    pub position_error_m: f64,
    /// Which sensor or scene produced it.
    pub source: String,
    pub pose: SensorPose,
    /// The region the sensor's rays covered, when the producer knows it
    /// (absent otherwise, and in messages from before the field existed):
    /// a consumer that finds it counts everything outside as unseen.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub field_of_view: Option<FieldOfView>,
    /// The directions in which the sensor's rays returned nothing, when the
    /// producer says (absent otherwise, and in messages from before the
    /// field existed): a consumer that finds it counts them as unseen, since
    /// a black object returns nothing, like empty space.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub no_return: Option<NoReturn>,
    /// `points * 4` bytes of little-endian f32 intensity, or absent.
    #[serde(with = "serde_bytes", default, skip_serializing_if = "Option::is_none")]
    pub intensity: Option<Vec<u8>>,
    /// Further per-point channels by name, `points * 4` bytes of
    /// little-endian f32 each (see [`PointChannel`]), or absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub channels: Option<ChannelBlobs>,
    /// `points * 12` bytes: x, y, z as little-endian f32, point after point.
    /// Last in the map (see [`CloudView::aligned`](super::CloudView::aligned)).
    #[serde(with = "serde_bytes")]
    pub points: Vec<u8>,
}

impl CloudMessage {
    pub fn new(
        stamp_ns: u64,
        sequence: u64,
        source: &str,
        pose: SensorPose,
        points: &[[f32; 3]],
    ) -> Self {
        Self {
            version: SCHEMA_VERSION,
            stamp_ns,
            sequence,
            pipeline_ns: 0,
            position_error_m: 0.0,
            source: source.to_owned(),
            pose,
            field_of_view: None,
            no_return: None,
            points: f32s_to_bytes(points.iter().flatten().copied()),
            intensity: None,
            channels: None,
        }
    }

    /// The same message with these channels (none: no `channels` field).
    pub fn with_channels(mut self, channels: &[PointChannel]) -> Self {
        self.channels = channels_to_blobs(channels);
        self
    }

    /// The channels, checked against the point count (empty when absent).
    pub fn channel_arrays(&self) -> Result<Vec<PointChannel>, MessageError> {
        let Some(blobs) = &self.channels else {
            return Ok(Vec::new());
        };
        check_channels(blobs, self.points.len() / 12)?;
        Ok(blobs_to_channels(blobs))
    }

    pub fn with_intensity(mut self, intensity: &[f32]) -> Self {
        self.intensity = Some(f32s_to_bytes(intensity.iter().copied()));
        self
    }

    // The decoder, `from_bytes`, goes through the borrowing view, so it is
    // defined with the view (cloud_view.rs), which builds on this type.
    pub fn to_bytes(&self) -> Result<Vec<u8>, MessageError> {
        encode(self)
    }

    /// The points as xyz triples.
    pub fn point_array(&self) -> Result<Vec<[f32; 3]>, MessageError> {
        if !self.points.len().is_multiple_of(12) {
            return Err(MessageError::BlobLength {
                field: "points",
                len: self.points.len(),
                unit: 12,
            });
        }
        let flat = bytes_to_f32s(&self.points, "points")?;
        Ok(flat.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect())
    }

    pub fn intensity_array(&self) -> Result<Option<Vec<f32>>, MessageError> {
        let Some(bytes) = &self.intensity else {
            return Ok(None);
        };
        let values = bytes_to_f32s(bytes, "intensity")?;
        let expected = self.points.len() / 12;
        if values.len() != expected {
            return Err(MessageError::Count {
                field: "intensity",
                found: values.len(),
                expected,
            });
        }
        Ok(Some(values))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> CloudMessage {
        CloudMessage::new(
            1_700_000_000_000_000_000,
            7,
            "sim/moving-spheres",
            SensorPose::default(),
            &[[1.0, 2.0, 3.0], [-4.5, 0.25, 1e-3]],
        )
        .with_intensity(&[0.5, 1.0])
        .with_channels(&[PointChannel::new("rcs", vec![5.0, -2.0])])
    }

    #[test]
    fn round_trips_and_keeps_the_documented_layout() {
        let msg = sample();
        let bytes = msg.to_bytes().unwrap();
        let back = CloudMessage::from_bytes(&bytes).unwrap();
        assert_eq!(back, msg);
        assert_eq!(
            back.point_array().unwrap(),
            vec![[1.0, 2.0, 3.0], [-4.5, 0.25, 1e-3]]
        );
        // Field names are in the map (a consumer in another language relies on them).
        let value: rmpv_like::Map = rmp_serde::from_slice(&bytes).unwrap();
        for key in [
            "version",
            "stamp_ns",
            "sequence",
            "source",
            "pose",
            "points",
            "intensity",
            "channels",
        ] {
            assert!(value.contains_key(key), "{key}");
        }
        // The points blob is raw little-endian f32 xyz.
        assert_eq!(&msg.points[0..4], &1.0f32.to_le_bytes());
        assert_eq!(msg.points.len(), 24);
    }

    #[test]
    fn bad_messages_are_named_errors() {
        let mut msg = sample();
        msg.points.pop();
        assert!(matches!(
            CloudMessage::from_bytes(&msg.to_bytes().unwrap()),
            Err(MessageError::BlobLength { .. })
        ));
        let mut msg = sample();
        msg.points[0..4].copy_from_slice(&f32::NAN.to_le_bytes());
        assert!(matches!(
            CloudMessage::from_bytes(&msg.to_bytes().unwrap()),
            Err(MessageError::NonFinite { .. })
        ));
        let mut msg = sample();
        msg.version = 99;
        assert!(matches!(
            CloudMessage::from_bytes(&msg.to_bytes().unwrap()),
            Err(MessageError::Version {
                message: "cloud",
                ..
            })
        ));
        let mut msg = sample();
        msg.channels.as_mut().unwrap().get_mut("rcs").unwrap().pop();
        assert!(matches!(
            CloudMessage::from_bytes(&msg.to_bytes().unwrap()),
            Err(MessageError::Count {
                field: "channels",
                ..
            })
        ));
        let mut msg = sample();
        msg.intensity = Some(vec![0; 4]);
        assert!(matches!(
            CloudMessage::from_bytes(&msg.to_bytes().unwrap()),
            Err(MessageError::Count { .. })
        ));
    }

    #[test]
    fn the_position_error_round_trips_and_old_messages_read_as_zero() {
        let mut msg = sample();
        msg.position_error_m = 0.125;
        let bytes = msg.to_bytes().unwrap();
        let back = CloudMessage::from_bytes(&bytes).unwrap();
        assert_eq!(back.position_error_m, 0.125);
        assert_eq!(back, msg);
        let view = super::super::CloudView::from_bytes(&bytes).unwrap();
        assert_eq!(view.position_error_m(), 0.125);
        // `points` stays last: the field goes before it in the map.
        let tail = &bytes[bytes.len() - msg.points.len() - 12..];
        assert!(tail.windows(6).any(|w| w == b"points"));
        // A message from before the field existed.
        #[derive(serde::Serialize)]
        struct Legacy<'a> {
            version: u16,
            stamp_ns: u64,
            sequence: u64,
            pipeline_ns: u64,
            source: &'a str,
            pose: SensorPose,
            #[serde(with = "serde_bytes")]
            points: &'a [u8],
        }
        let legacy = Legacy {
            version: msg.version,
            stamp_ns: msg.stamp_ns,
            sequence: msg.sequence,
            pipeline_ns: 3,
            source: &msg.source,
            pose: msg.pose,
            points: &msg.points,
        };
        let old = rmp_serde::to_vec_named(&legacy).unwrap();
        let read = CloudMessage::from_bytes(&old).unwrap();
        assert_eq!(read.position_error_m, 0.0);
        assert_eq!(read.point_array().unwrap(), msg.point_array().unwrap());
    }

    #[test]
    fn the_field_of_view_round_trips_is_validated_and_keeps_points_last() {
        let fov = super::super::sample_field_of_view();
        let mut msg = sample();
        msg.field_of_view = Some(fov);
        let bytes = msg.to_bytes().unwrap();
        assert_eq!(CloudMessage::from_bytes(&bytes).unwrap(), msg);
        let view = super::super::CloudView::from_bytes(&bytes).unwrap();
        assert_eq!(view.field_of_view, Some(fov));
        let tail = &bytes[bytes.len() - msg.points.len() - 12..];
        assert!(tail.windows(6).any(|w| w == b"points"));
        // Without one, the encoding is the one from before the field.
        assert!(!sample()
            .to_bytes()
            .unwrap()
            .windows(13)
            .any(|w| w == b"field_of_view"));
        msg.field_of_view = Some(FieldOfView {
            max_range: -1.0,
            ..fov
        });
        let e = CloudMessage::from_bytes(&msg.to_bytes().unwrap()).unwrap_err();
        assert!(e.to_string().contains("max_range"), "{e}");
        let view = super::super::CloudView::new(1, 2, "s", SensorPose::default(), &[]);
        assert!(view.with_field_of_view(msg.field_of_view.unwrap()).is_err());
    }

    #[test]
    fn directions_without_return_round_trip_and_are_validated() {
        let no_return = super::super::sample_no_return();
        let mut msg = sample();
        msg.no_return = Some(no_return.clone());
        let bytes = msg.to_bytes().unwrap();
        assert_eq!(CloudMessage::from_bytes(&bytes).unwrap(), msg);
        let tail = &bytes[bytes.len() - msg.points.len() - 12..];
        assert!(tail.windows(6).any(|w| w == b"points"));
        assert!(!sample()
            .to_bytes()
            .unwrap()
            .windows(9)
            .any(|w| w == b"no_return"));
        let mut bad = no_return;
        bad.cones[0].axis = [0.0, 0.0, 2.0];
        msg.no_return = Some(bad.clone());
        let e = CloudMessage::from_bytes(&msg.to_bytes().unwrap()).unwrap_err();
        assert!(e.to_string().contains("cone 0: axis"), "{e}");
        let view = super::super::CloudView::new(1, 2, "s", SensorPose::default(), &[]);
        assert!(view.with_no_return(bad).is_err());
    }

    #[test]
    fn a_position_error_that_is_no_distance_is_a_named_error() {
        for bad in [f64::NAN, -0.5, f64::INFINITY, f64::NEG_INFINITY] {
            let mut msg = sample();
            msg.position_error_m = bad;
            let bytes = msg.to_bytes().unwrap();
            assert!(
                matches!(
                    CloudMessage::from_bytes(&bytes),
                    Err(MessageError::PositionError { .. })
                ),
                "{bad}"
            );
            let view = super::super::CloudView::new(1, 2, "s", SensorPose::default(), &[]);
            assert!(matches!(
                view.with_position_error_m(bad),
                Err(MessageError::PositionError { .. })
            ));
        }
    }

    #[test]
    fn truncated_and_garbage_bytes_never_panic() {
        let bytes = sample().to_bytes().unwrap();
        for len in 0..bytes.len() {
            assert!(CloudMessage::from_bytes(&bytes[..len]).is_err());
        }
        let mut x = 0x9E37_79B9u32;
        for _ in 0..2000 {
            let garbage: Vec<u8> = (0..64)
                .map(|_| {
                    x ^= x << 13;
                    x ^= x >> 17;
                    x ^= x << 5;
                    x as u8
                })
                .collect();
            let _ = CloudMessage::from_bytes(&garbage);
        }
    }

    /// A generic map view for checking field names without a schema.
    mod rmpv_like {
        pub type Map = std::collections::BTreeMap<String, serde::de::IgnoredAny>;
    }
}
