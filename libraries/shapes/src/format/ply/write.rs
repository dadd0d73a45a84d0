//! Writing point clouds as PLY (binary little endian by default, or ASCII): the
//! one place that writes the header and vertex records of PLY point clouds
//! (plain clouds here, blended models through `blend::write_ply_with_normals`).

use crate::format::point_rows::{push_records, Column};

/// A property of every vertex after x, y, z: its PLY name and one value per point.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PlyProperty<'a> {
    pub name: &'a str,
    pub values: Column<'a>,
}

impl<'a> PlyProperty<'a> {
    pub(crate) fn float(name: &'a str, values: &'a [f32]) -> Self {
        let values = Column::F32(values);
        Self { name, values }
    }

    pub(crate) fn uchar(name: &'a str, values: &'a [u8]) -> Self {
        let values = Column::U8(values);
        Self { name, values }
    }

    fn type_name(&self) -> &'static str {
        match self.values {
            Column::F32(_) => "float",
            Column::U8(_) => "uchar",
        }
    }
}

/// The vertices of a PLY file: float x, y, z, then `properties` in order, with
/// `comment` (who wrote the file) as the header's comment line.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PlyVertices<'a> {
    pub comment: &'a str,
    pub points: &'a [[f32; 3]],
    pub properties: &'a [PlyProperty<'a>],
}

/// A PLY file of `points` with float x, y, z and, when `intensity` holds exactly
/// one value per point, a float `intensity` property (otherwise it is left out).
/// ASCII numbers use the shortest representation that reads back to the same f32.
pub fn write_ply_points(points: &[[f32; 3]], intensity: Option<&[f32]>, ascii: bool) -> Vec<u8> {
    let intensity = intensity.map(|values| PlyProperty::float("intensity", values));
    let vertices = PlyVertices {
        comment: "written by shroud",
        points,
        properties: intensity.as_slice(),
    };
    write_ply_vertices(&vertices, ascii)
}

/// A PLY file of `vertices`. A property without exactly one value per point is
/// left out rather than misalign the records.
pub(crate) fn write_ply_vertices(vertices: &PlyVertices, ascii: bool) -> Vec<u8> {
    let properties: Vec<PlyProperty> = vertices
        .properties
        .iter()
        .filter(|p| p.values.len() == vertices.points.len())
        .copied()
        .collect();
    let mut out = header(vertices, &properties, ascii).into_bytes();
    let columns: Vec<Column> = properties.iter().map(|p| p.values).collect();
    push_records(&mut out, vertices.points, &columns, ascii);
    out
}

fn header(vertices: &PlyVertices, properties: &[PlyProperty], ascii: bool) -> String {
    let encoding = if ascii {
        "ascii"
    } else {
        "binary_little_endian"
    };
    let mut header = format!(
        "ply\nformat {encoding} 1.0\ncomment {}\nelement vertex {}\n\
         property float x\nproperty float y\nproperty float z\n",
        vertices.comment,
        vertices.points.len()
    );
    for property in properties {
        header.push_str(&format!(
            "property {} {}\n",
            property.type_name(),
            property.name
        ));
    }
    header.push_str("end_header\n");
    header
}

#[cfg(test)]
mod tests {
    use super::*;

    const POINTS: [[f32; 3]; 2] = [[1.0, -0.1, 3e-8], [4.0, 5.0, 6.5]];
    const INTENSITY: [f32; 2] = [7.0, 0.5];

    fn hex(text: &str) -> Vec<u8> {
        (0..text.len())
            .step_by(2)
            .map(|i| u8::from_str_radix(&text[i..i + 2], 16).unwrap())
            .collect()
    }

    fn header_of(encoding: &str, intensity: bool) -> String {
        let extra = if intensity {
            "property float intensity\n"
        } else {
            ""
        };
        format!(
            "ply\nformat {encoding} 1.0\ncomment written by shroud\nelement vertex 2\n\
             property float x\nproperty float y\nproperty float z\n{extra}end_header\n"
        )
    }

    /// The bytes `write_ply_points` wrote before it became a call into
    /// `write_ply_vertices`: files saved earlier and by this version are the same.
    #[test]
    fn points_bytes_are_unchanged() {
        let cases = [
            (
                true,
                false,
                "31202d302e3120302e30303030303030330a34203520362e350a",
            ),
            (
                true,
                true,
                "31202d302e3120302e303030303030303320370a34203520362e3520302e350a",
            ),
            (
                false,
                false,
                "0000803fcdccccbd59d90033000080400000a0400000d040",
            ),
            (
                false,
                true,
                "0000803fcdccccbd59d900330000e040000080400000a0400000d0400000003f",
            ),
        ];
        for (ascii, has_intensity, body) in cases {
            let encoding = if ascii {
                "ascii"
            } else {
                "binary_little_endian"
            };
            let mut expected = header_of(encoding, has_intensity).into_bytes();
            expected.extend(hex(body));
            let intensity = has_intensity.then_some(&INTENSITY[..]);
            assert_eq!(write_ply_points(&POINTS, intensity, ascii), expected);
        }
        let short = write_ply_points(&POINTS, Some(&INTENSITY[..1]), true);
        assert_eq!(short, write_ply_points(&POINTS, None, true));
    }
}
