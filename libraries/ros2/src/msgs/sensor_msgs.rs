//! sensor_msgs (common_interfaces, Jazzy): PointField.msg, PointCloud2.msg,
//! JointState.msg and CompressedImage.msg.

use super::std_msgs::Header;
use crate::cdr::{decode_payload_with, CdrDecode, CdrEncode, CdrError, CdrReader, CdrWriter};
use crate::msgs::RosMessage;
use std::borrow::Cow;

ros_message! {
    /// One channel of a cloud's points (sensor_msgs/msg/PointField).
    "sensor_msgs/msg/PointField",
    "RIHS01_5c6a4750728c2bcfbbf7037225b20b02d4429634732146b742dee1726637ef01";
    pub struct PointField {
        pub name: String,
        /// Its byte offset within a point.
        pub offset: u32,
        /// One of the datatype constants.
        pub datatype: u8,
        /// How many values of `datatype` follow at `offset`.
        pub count: u32,
    }
}

impl PointField {
    pub const INT8: u8 = 1;
    pub const UINT8: u8 = 2;
    pub const INT16: u8 = 3;
    pub const UINT16: u8 = 4;
    pub const INT32: u8 = 5;
    pub const UINT32: u8 = 6;
    pub const FLOAT32: u8 = 7;
    pub const FLOAT64: u8 = 8;

    /// One value of `datatype` named `name` at byte `offset` of a point (the
    /// shape of every x, y, z and intensity channel).
    pub fn scalar(name: &str, offset: u32, datatype: u8) -> Self {
        Self {
            name: name.to_owned(),
            offset,
            datatype,
            count: 1,
        }
    }
}

ros_message! {
    /// Joint positions, velocities and efforts by name
    /// (sensor_msgs/msg/JointState); an empty array means "not reported".
    "sensor_msgs/msg/JointState",
    "RIHS01_a13ee3a330e346c9d87b5aa18d24e11690752bd33a0350f11c5882bc9179260e";
    pub struct JointState {
        pub header: Header,
        pub name: Vec<String>,
        pub position: Vec<f64>,
        pub velocity: Vec<f64>,
        pub effort: Vec<f64>,
    }
}

ros_message! {
    /// An encoded image (sensor_msgs/msg/CompressedImage).
    "sensor_msgs/msg/CompressedImage",
    "RIHS01_15640771531571185e2efc8a100baf923961a4d15d5569652e6cb6691e8e371a";
    pub struct CompressedImage {
        pub header: Header,
        /// `jpeg`, `png`, ...
        pub format: String,
        pub data: Vec<u8>,
    }
}

/// A point cloud (sensor_msgs/msg/PointCloud2): `height` rows of `width`
/// points of `point_step` bytes laid out by `fields`. `data` borrows from the
/// payload when decoded with [`PointCloud2::decode_borrowed`].
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PointCloud2<'a> {
    pub header: Header,
    pub height: u32,
    pub width: u32,
    pub fields: Vec<PointField>,
    /// The byte order of `data`'s values (not of the CDR around it).
    pub is_bigendian: bool,
    pub point_step: u32,
    pub row_step: u32,
    pub data: Cow<'a, [u8]>,
    /// True when no point is invalid (NaN).
    pub is_dense: bool,
}

impl<'a> PointCloud2<'a> {
    pub const TYPE_NAME: &'static str = "sensor_msgs/msg/PointCloud2";
    pub const TYPE_HASH: &'static str =
        "RIHS01_9198cabf7da3796ae6fe19c4cb3bdd3525492988c70522628af5daa124bae2b5";

    /// Reads a whole payload without copying `data`.
    pub fn decode_borrowed(bytes: &'a [u8]) -> Result<Self, CdrError> {
        decode_payload_with(bytes, Self::read)
    }

    /// The whole payload: CDR_LE header and the cloud, written into a
    /// buffer sized for it up front (`shroud-bench ros2-cdr` measures this).
    pub fn encode(&self) -> Vec<u8> {
        let mut writer = CdrWriter::with_capacity(self.encoded_len_hint());
        self.encode_cdr(&mut writer);
        writer.into_bytes()
    }

    /// The payload's length, give or take padding: the data, the strings and
    /// a bound on every fixed-size part and its alignment.
    fn encoded_len_hint(&self) -> usize {
        const FIXED: usize = 64;
        const PER_FIELD: usize = 24;
        let names: usize = self.fields.iter().map(|f| f.name.len()).sum();
        FIXED + self.header.frame_id.len() + self.fields.len() * PER_FIELD + names + self.data.len()
    }

    /// The same cloud owning its data.
    pub fn into_owned(self) -> PointCloud2<'static> {
        PointCloud2 {
            data: Cow::Owned(self.data.into_owned()),
            ..self
        }
    }

    fn read(reader: &mut CdrReader<'a>) -> Result<Self, CdrError> {
        Ok(Self {
            header: Header::decode_cdr(reader, "PointCloud2.header")?,
            height: reader.u32("PointCloud2.height")?,
            width: reader.u32("PointCloud2.width")?,
            fields: Vec::decode_cdr(reader, "PointCloud2.fields")?,
            is_bigendian: reader.bool("PointCloud2.is_bigendian")?,
            point_step: reader.u32("PointCloud2.point_step")?,
            row_step: reader.u32("PointCloud2.row_step")?,
            data: Cow::Borrowed(reader.byte_sequence("PointCloud2.data")?),
            is_dense: reader.bool("PointCloud2.is_dense")?,
        })
    }
}

impl CdrEncode for PointCloud2<'_> {
    fn encode_cdr(&self, writer: &mut CdrWriter) {
        self.header.encode_cdr(writer);
        writer.u32(self.height);
        writer.u32(self.width);
        self.fields.encode_cdr(writer);
        writer.bool(self.is_bigendian);
        writer.u32(self.point_step);
        writer.u32(self.row_step);
        writer.byte_sequence(&self.data);
        writer.bool(self.is_dense);
    }
}

/// Decoding into an owned cloud copies `data`.
impl CdrDecode for PointCloud2<'static> {
    /// Header, 3 u32 and 2 bools, 2 u32, 2 sequence counts.
    const MIN_CDR_BYTES: usize = Header::MIN_CDR_BYTES + 4 * 4 + 2 + 3 * 4;

    fn decode_cdr(reader: &mut CdrReader<'_>, _field: &'static str) -> Result<Self, CdrError> {
        PointCloud2::read(reader).map(PointCloud2::into_owned)
    }
}

impl RosMessage for PointCloud2<'static> {
    const TYPE_NAME: &'static str = PointCloud2::TYPE_NAME;
    const TYPE_HASH: &'static str = PointCloud2::TYPE_HASH;
}
