//! Where a `PointCloud2`'s x, y, z and intensity sit in each point's bytes
//! (`sensor_msgs/msg/PointField`: a name, a byte offset in the point, a
//! datatype), checked against the point step, the row step and the data's
//! length before any point is read.

use crate::CloudInError;
use shroud_ros2::{PointCloud2, PointField};

/// One number of a point: its byte offset and `PointField` datatype.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Scalar {
    pub offset: usize,
    pub datatype: u8,
}

/// A cloud's layout, valid for its data: every field inside the point step,
/// every point inside its row, every row inside the data.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PointLayout {
    pub x: Scalar,
    pub y: Scalar,
    pub z: Scalar,
    pub intensity: Option<Scalar>,
    pub point_step: usize,
    pub row_step: usize,
    pub width: usize,
    pub height: usize,
    pub big_endian: bool,
}

/// Bytes of a `PointField` datatype (INT8 = 1 ... FLOAT64 = 8), `None` for
/// any other value.
fn datatype_size(datatype: u8) -> Option<usize> {
    match datatype {
        PointField::INT8 | PointField::UINT8 => Some(1),
        PointField::INT16 | PointField::UINT16 => Some(2),
        PointField::INT32 | PointField::UINT32 | PointField::FLOAT32 => Some(4),
        PointField::FLOAT64 => Some(8),
        _ => None,
    }
}

impl Scalar {
    /// The number at this scalar's place in `point` (which holds it: the
    /// layout checked so), as f64.
    pub fn read(self, point: &[u8], big_endian: bool) -> f64 {
        let at = |n: usize| -> [u8; 8] {
            let mut b = [0u8; 8];
            b[..n].copy_from_slice(&point[self.offset..self.offset + n]);
            if big_endian {
                b[..n].reverse();
            }
            b
        };
        match self.datatype {
            PointField::INT8 => f64::from(point[self.offset] as i8),
            PointField::UINT8 => f64::from(point[self.offset]),
            PointField::INT16 => f64::from(i16::from_le_bytes([at(2)[0], at(2)[1]])),
            PointField::UINT16 => f64::from(u16::from_le_bytes([at(2)[0], at(2)[1]])),
            PointField::INT32 => f64::from(i32::from_le_bytes(first4(at(4)))),
            PointField::UINT32 => f64::from(u32::from_le_bytes(first4(at(4)))),
            PointField::FLOAT32 => f64::from(f32::from_le_bytes(first4(at(4)))),
            _ => f64::from_le_bytes(at(8)),
        }
    }
}

fn first4(b: [u8; 8]) -> [u8; 4] {
    [b[0], b[1], b[2], b[3]]
}

impl PointLayout {
    /// The layout of `cloud`: fields `x`, `y`, `z` (FLOAT32 or FLOAT64) and,
    /// when present, `intensity` (any number type); a field with a count
    /// above 1 is read at its first element.
    pub fn of(cloud: &PointCloud2<'_>) -> Result<Self, CloudInError> {
        if cloud.point_step == 0 {
            return Err(CloudInError::ZeroPointStep);
        }
        let coordinate = |name: &'static str| {
            let scalar = field(cloud, name)?.ok_or_else(|| CloudInError::MissingField {
                name,
                found: field_names(cloud),
            })?;
            match scalar.datatype {
                PointField::FLOAT32 | PointField::FLOAT64 => Ok(scalar),
                datatype => Err(CloudInError::CoordinateType {
                    name: name.into(),
                    datatype,
                }),
            }
        };
        let layout = Self {
            x: coordinate("x")?,
            y: coordinate("y")?,
            z: coordinate("z")?,
            intensity: field(cloud, "intensity")?,
            point_step: cloud.point_step as usize,
            row_step: cloud.row_step as usize,
            width: cloud.width as usize,
            height: cloud.height as usize,
            big_endian: cloud.is_bigendian,
        };
        check_extent(cloud)?;
        Ok(layout)
    }

    /// Points in the cloud: `width * height`, which the data holds.
    pub fn len(&self) -> usize {
        self.width * self.height
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// A point's x, y, z (its bytes from [`Self::point`]).
    pub fn xyz(&self, point: &[u8]) -> glam::DVec3 {
        let be = self.big_endian;
        glam::DVec3::new(
            self.x.read(point, be),
            self.y.read(point, be),
            self.z.read(point, be),
        )
    }

    /// The bytes of point `(row, column)`.
    pub fn point<'d>(&self, data: &'d [u8], row: usize, column: usize) -> &'d [u8] {
        let start = row * self.row_step + column * self.point_step;
        &data[start..start + self.point_step]
    }
}

/// The field `name` as a scalar inside the point step, `None` when the
/// cloud has no such field.
fn field(cloud: &PointCloud2<'_>, name: &str) -> Result<Option<Scalar>, CloudInError> {
    let Some(f) = cloud.fields.iter().find(|f| f.name == name) else {
        return Ok(None);
    };
    let size = datatype_size(f.datatype).ok_or_else(|| CloudInError::FieldType {
        name: name.into(),
        datatype: f.datatype,
    })?;
    if u64::from(f.offset) + size as u64 > u64::from(cloud.point_step) {
        return Err(CloudInError::FieldOutside {
            name: name.into(),
            offset: f.offset,
            size,
            point_step: cloud.point_step,
        });
    }
    Ok(Some(Scalar {
        offset: f.offset as usize,
        datatype: f.datatype,
    }))
}

fn field_names(cloud: &PointCloud2<'_>) -> String {
    let names: Vec<&str> = cloud.fields.iter().map(|f| f.name.as_str()).collect();
    format!("[{}]", names.join(", "))
}

/// Every row's points inside its row step, and exactly `row_step * height`
/// bytes of data (PointCloud2.msg: "actual point data, size is (row_step*height)").
fn check_extent(cloud: &PointCloud2<'_>) -> Result<(), CloudInError> {
    let row_bytes = u64::from(cloud.width) * u64::from(cloud.point_step);
    if cloud.height > 0 && row_bytes > u64::from(cloud.row_step) {
        return Err(CloudInError::RowTooShort {
            width: cloud.width,
            point_step: cloud.point_step,
            row_step: cloud.row_step,
        });
    }
    let expected = u128::from(cloud.row_step) * u128::from(cloud.height);
    if cloud.data.len() as u128 != expected {
        return Err(CloudInError::DataLength {
            found: cloud.data.len(),
            row_step: cloud.row_step,
            height: cloud.height,
            expected,
        });
    }
    Ok(())
}
