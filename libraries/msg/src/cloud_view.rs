//! Point clouds without copies: a view that borrows its blobs, for encoding
//! straight from `&[[f32; 3]]` into a transport buffer and decoding straight from
//! a received payload. Same wire layout as [`CloudMessage`], whose decoder
//! ([`CloudMessage::from_bytes`]) goes through this view and so is defined here:
//! the view builds on the owned message, never the other way round.

use super::channels::{channels_to_blobs, check_channels, ChannelBlobs, PointChannel};
use super::error::MessageError;
use super::{check_version, CloudMessage, FieldOfView, NoReturn, SensorPose, SCHEMA_VERSION};
use serde::{Deserialize, Serialize};
use std::borrow::Cow;

/// A point-cloud message whose strings and blobs borrow someone else's bytes.
///
/// `points` is the map's last entry, so that the encoding's length is the
/// points' offset plus `12 N`, a multiple of 4 when the offset is.
///
/// Field for field the [`CloudMessage`] map: either type decodes what the other
/// encodes. On little-endian machines (every robot we know of) encoding takes
/// the points' bytes as they are in memory and decoding is one `memcpy`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CloudView<'a> {
    pub version: u16,
    pub stamp_ns: u64,
    pub sequence: u64,
    /// See [`CloudMessage::pipeline_ns`].
    pub pipeline_ns: u64,
    /// See [`CloudMessage::position_error_m`].
    #[serde(default)]
    pub position_error_m: f64,
    #[serde(borrow)]
    pub source: Cow<'a, str>,
    pub pose: SensorPose,
    /// See [`CloudMessage::field_of_view`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub field_of_view: Option<FieldOfView>,
    /// See [`CloudMessage::no_return`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub no_return: Option<NoReturn>,
    #[serde(
        borrow,
        with = "serde_bytes",
        default,
        skip_serializing_if = "Option::is_none"
    )]
    pub intensity: Option<Cow<'a, [u8]>>,
    /// See [`CloudMessage::channels`]: small (radar returns), so owned.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub channels: Option<ChannelBlobs>,
    /// 0 to 3 zero bytes that put the `points` blob on a 4-byte boundary of the
    /// payload (see [`Self::aligned`]); absent when none are needed. Decoders
    /// ignore it.
    #[serde(
        borrow,
        with = "serde_bytes",
        default,
        skip_serializing_if = "Option::is_none"
    )]
    pub align: Option<Cow<'a, [u8]>>,
    #[serde(borrow, with = "serde_bytes")]
    pub points: Cow<'a, [u8]>,
}

impl<'a> CloudView<'a> {
    /// A message over `points` (no copy on little-endian machines).
    pub fn new(
        stamp_ns: u64,
        sequence: u64,
        source: &'a str,
        pose: SensorPose,
        points: &'a [[f32; 3]],
    ) -> Self {
        Self {
            version: SCHEMA_VERSION,
            stamp_ns,
            sequence,
            pipeline_ns: 0,
            position_error_m: 0.0,
            source: Cow::Borrowed(source),
            pose,
            field_of_view: None,
            no_return: None,
            align: None,
            points: le_bytes(bytemuck::cast_slice(points)),
            intensity: None,
            channels: None,
        }
    }

    /// The same message with these channels (copied; none: no field).
    pub fn with_channels(mut self, channels: &[PointChannel]) -> Self {
        self.channels = channels_to_blobs(channels);
        self
    }

    /// The same message with one intensity per point (no copy on little-endian
    /// machines).
    pub fn with_intensity(mut self, intensity: &'a [f32]) -> Self {
        self.intensity = Some(le_bytes(bytemuck::cast_slice(intensity)));
        self
    }

    /// The same message with the time spent in shroud nodes so far
    /// ([`CloudMessage::pipeline_ns`]).
    pub fn with_pipeline_ns(mut self, pipeline_ns: u64) -> Self {
        self.pipeline_ns = pipeline_ns;
        self
    }

    /// The same message with a bound on its points' position error
    /// ([`CloudMessage::position_error_m`]); refused unless finite and >= 0.
    pub fn with_position_error_m(mut self, metres: f64) -> Result<Self, MessageError> {
        check_position_error(metres)?;
        self.position_error_m = metres;
        Ok(self)
    }

    /// The same message with the region its sensor's rays covered
    /// ([`CloudMessage::field_of_view`]); refused unless it is convex.
    pub fn with_field_of_view(mut self, fov: FieldOfView) -> Result<Self, MessageError> {
        fov.validate()?;
        self.field_of_view = Some(fov);
        Ok(self)
    }

    /// The same message with the directions in which its sensor's rays
    /// returned nothing ([`CloudMessage::no_return`]); refused unless valid.
    pub fn with_no_return(mut self, no_return: NoReturn) -> Result<Self, MessageError> {
        no_return.validate()?;
        self.no_return = Some(no_return);
        Ok(self)
    }

    /// The bound on the points' position error, metres
    /// ([`CloudMessage::position_error_m`]).
    pub fn position_error_m(&self) -> f64 {
        self.position_error_m
    }

    /// The same message with an `align` field that puts the points blob at a
    /// multiple of 4 bytes from the start of the encoding. Encoded into a
    /// 4-byte-aligned buffer (shared memory), the receiver can then read the
    /// floats where they lie instead of copying them ([`Self::points_in_place`]).
    pub fn aligned(mut self) -> Result<Self, MessageError> {
        self.align = None;
        let offset = self.points_offset()?;
        // An `align` entry costs 8 bytes (key "align" 6, bin8 header 2) plus its
        // payload: pad so that the total shift is a multiple of 4.
        let pad = (4 - offset % 4) % 4;
        if pad != 0 {
            self.align = Some(Cow::Owned(vec![0; pad]));
        }
        Ok(self)
    }

    /// Where the points blob starts in this message's encoding: it is the
    /// last entry, so its data ends the encoding.
    fn points_offset(&self) -> Result<usize, MessageError> {
        Ok(super::encoded_len(self)? - self.points.len())
    }

    /// The points as they lie in the payload, when the blob is 4-byte aligned in
    /// memory (an [`Self::aligned`] message in an aligned buffer) on a
    /// little-endian machine; `None` otherwise, and the caller copies with
    /// [`Self::read_points`]. Refuses NaN and infinities like `read_points`.
    pub fn points_in_place(&self) -> Option<Result<&[[f32; 3]], MessageError>> {
        let points = self.raw_points_in_place()?;
        let flat: &[f32] = bytemuck::cast_slice(points);
        let all_finite = flat.iter().fold(true, |ok, v| ok & v.is_finite());
        Some(if all_finite {
            Ok(points)
        } else {
            Err(non_finite(flat))
        })
    }

    /// [`Self::points_in_place`] without the finiteness check, for a consumer
    /// that validates the points in its own first pass anyway (the surrogate
    /// fitter refuses a non-finite point and names it): at 300K points the
    /// check is a tenth of the transport's overhead.
    pub fn raw_points_in_place(&self) -> Option<&[[f32; 3]]> {
        if cfg!(target_endian = "big") {
            return None;
        }
        bytemuck::try_cast_slice(&self.points).ok()
    }

    /// Decodes the header and borrows the blobs, checking the version, the pose
    /// and the blobs' lengths. Point values are checked by [`Self::read_points`].
    pub fn from_bytes(bytes: &'a [u8]) -> Result<Self, MessageError> {
        let view: CloudView<'a> = super::blob::decode(bytes)?;
        check_version("cloud", view.version, SCHEMA_VERSION)?;
        check_position_error(view.position_error_m)?;
        if let Some(fov) = &view.field_of_view {
            fov.validate()?;
        }
        if let Some(no_return) = &view.no_return {
            no_return.validate()?;
        }
        let pose = view.pose.position.iter().chain(&view.pose.orientation);
        if let Some(index) = pose.clone().position(|v| !v.is_finite()) {
            return Err(MessageError::NonFinite {
                field: "pose",
                index,
            });
        }
        if !view.points.len().is_multiple_of(12) {
            return Err(MessageError::BlobLength {
                field: "points",
                len: view.points.len(),
                unit: 12,
            });
        }
        if let Some(intensity) = &view.intensity {
            let expected = view.len();
            if intensity.len() != 4 * expected {
                return Err(MessageError::Count {
                    field: "intensity",
                    found: intensity.len() / 4,
                    expected,
                });
            }
        }
        if let Some(channels) = &view.channels {
            check_channels(channels, view.len())?;
        }
        Ok(view)
    }

    /// Refuses a NaN or an infinity among the points, naming the first
    /// (for consumers that read the blob where it lies instead of copying it).
    pub fn check_finite_points(&self) -> Result<(), MessageError> {
        let floats = self.points.as_chunks::<4>().0;
        match floats
            .iter()
            .position(|c| !f32::from_le_bytes(*c).is_finite())
        {
            Some(index) => Err(MessageError::NonFinite {
                field: "points",
                index: index / 3,
            }),
            None => Ok(()),
        }
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.points.len() / 12
    }

    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// Replaces `out` with the points, refusing NaN and infinities. `out` keeps
    /// its allocation from frame to frame.
    pub fn read_points(&self, out: &mut Vec<[f32; 3]>) -> Result<(), MessageError> {
        // Resizing a reused buffer of the same length writes nothing; the copy is
        // one memcpy and the check one branch-free pass that vectorises.
        out.resize(self.len(), [0.0; 3]);
        let flat: &mut [f32] = bytemuck::cast_slice_mut(out.as_mut_slice());
        let all_finite = copy_le_f32s(&self.points, flat);
        if all_finite {
            return Ok(());
        }
        let error = non_finite(flat);
        out.clear();
        Err(error)
    }

    /// The encoded message, in a new vector.
    pub fn to_bytes(&self) -> Result<Vec<u8>, MessageError> {
        super::blob::encode(self)
    }

    /// An owned copy, validated like [`CloudMessage::from_bytes`].
    pub fn to_message(&self) -> Result<CloudMessage, MessageError> {
        let msg = CloudMessage {
            version: self.version,
            stamp_ns: self.stamp_ns,
            sequence: self.sequence,
            pipeline_ns: self.pipeline_ns,
            position_error_m: self.position_error_m,
            source: self.source.clone().into_owned(),
            pose: self.pose,
            field_of_view: self.field_of_view,
            no_return: self.no_return.clone(),
            points: self.points.to_vec(),
            intensity: self.intensity.as_ref().map(|i| i.to_vec()),
            channels: self.channels.clone(),
        };
        msg.point_array()?;
        msg.intensity_array()?;
        msg.channel_arrays()?;
        Ok(msg)
    }
}

impl CloudMessage {
    /// Decodes and validates: version, blob lengths, finite values, pose.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, MessageError> {
        CloudView::from_bytes(bytes)?.to_message()
    }
}

/// A position error bound must be a distance: finite and not negative.
fn check_position_error(metres: f64) -> Result<(), MessageError> {
    if metres.is_finite() && metres >= 0.0 {
        Ok(())
    } else {
        Err(MessageError::PositionError { value: metres })
    }
}

/// The error for a blob that holds a NaN or an infinity.
fn non_finite(flat: &[f32]) -> MessageError {
    MessageError::NonFinite {
        field: "points",
        index: flat.iter().position(|v| !v.is_finite()).unwrap_or(0),
    }
}

/// Copies little-endian f32 bytes into `dst`; true when every value is finite.
fn copy_le_f32s(src: &[u8], dst: &mut [f32]) -> bool {
    bytemuck::cast_slice_mut::<f32, u8>(dst).copy_from_slice(src);
    if cfg!(target_endian = "big") {
        for v in dst.iter_mut() {
            *v = f32::from_bits(u32::from_le(v.to_bits()));
        }
    }
    dst.iter().fold(true, |ok, v| ok & v.is_finite())
}

/// Native f32 bytes as little-endian bytes: borrowed where they already are.
fn le_bytes(native: &[u8]) -> Cow<'_, [u8]> {
    if cfg!(target_endian = "little") {
        Cow::Borrowed(native)
    } else {
        let floats: &[f32] = bytemuck::cast_slice(native);
        Cow::Owned(floats.iter().flat_map(|v| v.to_le_bytes()).collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const POINTS: [[f32; 3]; 3] = [[1.0, 2.0, 3.0], [-4.5, 0.25, 1e-3], [0.0, -0.0, 7.0]];

    #[test]
    fn view_and_owned_message_read_each_other() {
        let view = CloudView::new(5, 9, "sim/x", SensorPose::default(), &POINTS);
        let bytes = view.to_bytes().unwrap();
        let owned = CloudMessage::from_bytes(&bytes).unwrap();
        assert_eq!(owned.point_array().unwrap(), POINTS.to_vec());
        assert_eq!(owned.to_bytes().unwrap(), bytes);
        let back = CloudView::from_bytes(&bytes).unwrap();
        assert!(matches!(back.points, Cow::Borrowed(_)), "decoding copied");
        let mut out = vec![[9.0; 3]; 17];
        back.read_points(&mut out).unwrap();
        assert_eq!(out, POINTS.to_vec());
        assert_eq!(back.to_message().unwrap(), owned);
    }

    #[test]
    fn encoded_len_and_encode_into_match_to_bytes() {
        let view = CloudView::new(5, 9, "sim/x", SensorPose::default(), &POINTS);
        let bytes = view.to_bytes().unwrap();
        assert_eq!(super::super::encoded_len(&view).unwrap(), bytes.len());
        let mut buf = vec![0u8; bytes.len()];
        super::super::encode_into(&view, &mut buf).unwrap();
        assert_eq!(buf, bytes);
        let mut short = vec![0u8; bytes.len() - 1];
        assert!(super::super::encode_into(&view, &mut short).is_err());
    }

    #[test]
    fn aligned_messages_put_the_points_on_a_four_byte_boundary() {
        let pts: Vec<[f32; 3]> = (0..100).map(|i| [i as f32, 0.5, -1.0]).collect();
        // Sources of every length mod 4 exercise every padding.
        for source in ["", "a", "ab", "abc", "abcd", "sim/moving-spheres"] {
            for intensity in [false, true] {
                let mut view = CloudView::new(1, 2, source, SensorPose::default(), &pts);
                let values = vec![0.25f32; pts.len()];
                if intensity {
                    view.intensity = Some(Cow::Owned(bytemuck::cast_slice(&values).to_vec()));
                }
                let view = view.aligned().unwrap();
                // A u32 buffer is 4-byte aligned; the view decodes from its bytes.
                let len = super::super::encoded_len(&view).unwrap();
                assert_eq!(len % 4, 0, "an aligned message fills whole words");
                let mut words = vec![0u32; len.div_ceil(4)];
                let bytes = &mut bytemuck::cast_slice_mut::<u32, u8>(&mut words)[..len];
                super::super::encode_into(&view, bytes).unwrap();
                let back = CloudView::from_bytes(bytes).unwrap();
                let in_place = back.points_in_place().expect("aligned").unwrap();
                assert_eq!(in_place, &pts[..], "source {source:?}");
                // Decoders that do not know `align` read the same message.
                assert_eq!(
                    CloudMessage::from_bytes(bytes)
                        .unwrap()
                        .point_array()
                        .unwrap(),
                    pts
                );
            }
        }
    }

    #[test]
    fn in_place_points_refuse_non_finite_values() {
        let mut pts = vec![[1.0f32, 2.0, 3.0]; 10];
        pts[4][1] = f32::NAN;
        let view = CloudView::new(1, 2, "s", SensorPose::default(), &pts)
            .aligned()
            .unwrap();
        let len = super::super::encoded_len(&view).unwrap();
        let mut words = vec![0u32; len.div_ceil(4)];
        let bytes = &mut bytemuck::cast_slice_mut::<u32, u8>(&mut words)[..len];
        super::super::encode_into(&view, bytes).unwrap();
        let back = CloudView::from_bytes(bytes).unwrap();
        assert!(matches!(
            back.points_in_place(),
            Some(Err(MessageError::NonFinite { index: 13, .. }))
        ));
    }

    #[test]
    fn bad_views_are_named_errors() {
        let msg = CloudMessage::new(1, 2, "s", SensorPose::default(), &POINTS);
        let mut nan = msg.clone();
        nan.points[12..16].copy_from_slice(&f32::INFINITY.to_le_bytes());
        let bytes = nan.to_bytes().unwrap();
        let view = CloudView::from_bytes(&bytes).unwrap();
        let mut out = Vec::new();
        assert!(matches!(
            view.read_points(&mut out),
            Err(MessageError::NonFinite { index: 3, .. })
        ));
        assert!(out.is_empty());
        let mut short = msg.clone();
        short.points.pop();
        assert!(matches!(
            CloudView::from_bytes(&short.to_bytes().unwrap()),
            Err(MessageError::BlobLength { .. })
        ));
        let counted = msg.clone().with_intensity(&[1.0]);
        assert!(matches!(
            CloudView::from_bytes(&counted.to_bytes().unwrap()),
            Err(MessageError::Count { .. })
        ));
        let mut version = msg;
        version.version = SCHEMA_VERSION + 1;
        assert!(matches!(
            CloudView::from_bytes(&version.to_bytes().unwrap()),
            Err(MessageError::Version {
                message: "cloud",
                ..
            })
        ));
    }

    #[test]
    fn truncated_bytes_never_panic() {
        let bytes = CloudView::new(5, 9, "s", SensorPose::default(), &POINTS)
            .to_bytes()
            .unwrap();
        for len in 0..bytes.len() {
            assert!(CloudView::from_bytes(&bytes[..len]).is_err());
        }
    }
}
