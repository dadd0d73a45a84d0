//! Triangle meshes from PLY: the `vertex` element's x, y, z (at full precision)
//! and the `face` element's list of vertex indices. Elements before and between
//! them are walked with the same record readers as clouds; elements after both
//! are not read.

use super::ascii_body::{check_record_shape, parse_number, token_index, BodyLines};
use super::binary_body::{skip_element, walk_record, RecordError};
use super::header::{parse_header, Element, Encoding, Header, PropertyKind};
use super::layout::VertexLayout;
use crate::format::mesh_builder::MeshBuilder;
use crate::format::scalar::ScalarType;
use crate::format::{FormatError, TriangleMesh};

/// Names of the face list property, preferred in this order (ASCII
/// case-insensitive); without one of them the face element's first list is used.
const INDEX_NAMES: [&str; 2] = ["vertex_indices", "vertex_index"];

/// Where the faces and their index list are.
struct FaceLayout {
    /// Index of the face element among all elements.
    element: usize,
    /// Index of the index list among the face element's properties.
    list: usize,
}

impl FaceLayout {
    fn of(header: &Header) -> Result<Self, FormatError> {
        let element = header
            .elements
            .iter()
            .position(|e| e.name == "face" && e.count > 0)
            .ok_or(FormatError::PlyNoFaceElement)?;
        let properties = &header.elements[element].properties;
        let is_list = |i: &usize| matches!(properties[*i].kind, PropertyKind::List { .. });
        let named = INDEX_NAMES.iter().find_map(|name| {
            (0..properties.len())
                .find(|i| is_list(i) && properties[*i].name.eq_ignore_ascii_case(name))
        });
        let list = named
            .or_else(|| (0..properties.len()).find(is_list))
            .ok_or(FormatError::PlyNoFaceIndices)?;
        Ok(Self { element, list })
    }
}

/// What a mesh reader needs to know while walking the elements.
struct Plan<'a> {
    header: &'a Header,
    vertices: VertexLayout,
    faces: FaceLayout,
    /// Number of vertices the header declares (face indices must stay below it).
    vertex_count: usize,
}

impl Plan<'_> {
    /// The elements to walk: up to the later of vertex and face.
    fn elements(&self) -> impl Iterator<Item = (usize, &Element)> {
        let last = self.vertices.element.max(self.faces.element);
        self.header.elements[..=last].iter().enumerate()
    }

    /// A face's raw index values as `u32`, each checked to be an integer below
    /// the vertex count.
    fn indices(
        &self,
        record: usize,
        values: &[f64],
        out: &mut Vec<u32>,
    ) -> Result<(), FormatError> {
        out.clear();
        for &value in values {
            // NaN and infinities have a NaN fraction.
            if value < 0.0 || value.fract() != 0.0 {
                return Err(FormatError::MeshBadIndex {
                    location: face_location(record),
                    value,
                });
            }
            if value >= self.vertex_count as f64 {
                return Err(FormatError::MeshIndexOutOfRange {
                    location: face_location(record),
                    index: value.min(i64::MAX as f64) as i64,
                    vertices: self.vertex_count,
                });
            }
            out.push(value as u32);
        }
        Ok(())
    }
}

fn face_location(record: usize) -> String {
    format!("PLY face {record}")
}

fn vertex_location(record: usize) -> String {
    format!("PLY vertex {record}")
}

fn truncated(element: &Element, got: usize, offset: usize) -> FormatError {
    FormatError::PlyTruncatedElement {
        element: element.name.clone(),
        expected: element.count,
        got,
        offset,
    }
}

/// Reads a PLY file with a `vertex` and a `face` element as a triangle mesh.
pub(in crate::format) fn parse_ply_mesh(bytes: &[u8]) -> Result<TriangleMesh, FormatError> {
    let header = parse_header(bytes)?;
    let vertices = VertexLayout::of(&header)?;
    let faces = FaceLayout::of(&header)?;
    let vertex_count = header.elements[vertices.element].count;
    if vertex_count > u32::MAX as usize {
        return Err(FormatError::MeshTooManyVertices {
            count: vertex_count,
            max: u32::MAX as usize,
        });
    }
    // Every vertex record takes at least 3 bytes and every face record at least
    // 1: the declared counts are bounded by the input before allocating.
    let face_count = header.elements[faces.element].count;
    let mut builder = MeshBuilder::with_capacity(
        vertex_count.min(bytes.len() / 3),
        face_count.min(bytes.len()),
    );
    let plan = Plan {
        header: &header,
        vertices,
        faces,
        vertex_count,
    };
    match header.encoding {
        Encoding::Ascii => read_ascii(bytes, &plan, &mut builder)?,
        Encoding::BinaryLittleEndian => read_binary(bytes, &plan, &mut builder, false)?,
        Encoding::BinaryBigEndian => read_binary(bytes, &plan, &mut builder, true)?,
    }
    builder.finish()
}

fn read_binary(
    bytes: &[u8],
    plan: &Plan,
    builder: &mut MeshBuilder,
    big_endian: bool,
) -> Result<(), FormatError> {
    let mut pos = plan.header.body_offset;
    let mut values = Vec::new();
    let mut indices = Vec::new();
    for (index, element) in plan.elements() {
        let record_error = |record: usize, offset: usize, error: RecordError| match error {
            RecordError::Truncated => truncated(element, record, offset),
            RecordError::BadListLength(length) => FormatError::PlyBadListLength {
                element: element.name.clone(),
                record,
                length,
            },
        };
        if index == plan.vertices.element {
            let [x, y, z] = plan.vertices.xyz.map(|slot| slot.index);
            for record in 0..element.count {
                let mut xyz = [0.0; 3];
                let store = |property: usize, value: f64| {
                    if let Some(k) = [x, y, z].iter().position(|&p| p == property) {
                        xyz[k] = value;
                    }
                };
                pos = walk_record(bytes, pos, element, big_endian, store, |_, _, _| {})
                    .map_err(|e| record_error(record, pos, e))?;
                builder.vertex(xyz, || vertex_location(record))?;
            }
        } else if index == plan.faces.element {
            for record in 0..element.count {
                values.clear();
                let list = |property: usize, item: ScalarType, data: &[u8]| {
                    if property == plan.faces.list {
                        // `data` holds whole items: decoding cannot fail.
                        let decode =
                            |chunk: &[u8]| item.decode(chunk, big_endian).unwrap_or(f64::NAN);
                        values.extend(data.chunks_exact(item.size()).map(decode));
                    }
                };
                pos = walk_record(bytes, pos, element, big_endian, |_, _| {}, list)
                    .map_err(|e| record_error(record, pos, e))?;
                plan.indices(record, &values, &mut indices)?;
                builder.face(&indices, || face_location(record))?;
            }
        } else {
            pos = skip_element(bytes, pos, element, big_endian)
                .map_err(|(record, e)| record_error(record, pos, e))?;
        }
    }
    Ok(())
}

fn read_ascii(bytes: &[u8], plan: &Plan, builder: &mut MeshBuilder) -> Result<(), FormatError> {
    let mut lines = BodyLines::of(bytes, plan.header);
    let mut values = Vec::new();
    let mut indices = Vec::new();
    for (index, element) in plan.elements() {
        for record in 0..element.count {
            let (line, text) = lines
                .next_record()?
                .ok_or_else(|| truncated(element, record, lines.offset()))?;
            let tokens: Vec<&str> = text.split_ascii_whitespace().collect();
            check_record_shape(element, &tokens, line)?;
            // The shape check guarantees a token for every property and list item.
            let token = |i: usize| tokens.get(i).copied().unwrap_or_default();
            if index == plan.vertices.element {
                let mut xyz = [0.0; 3];
                for (k, slot) in plan.vertices.xyz.iter().enumerate() {
                    let at = token_index(element, slot.index, &tokens);
                    xyz[k] = parse_number(token(at), slot.ty, line)?;
                }
                builder.vertex(xyz, || vertex_location(record))?;
            } else if index == plan.faces.element {
                let PropertyKind::List { count, item } = element.properties[plan.faces.list].kind
                else {
                    return Err(FormatError::PlyNoFaceIndices);
                };
                let at = token_index(element, plan.faces.list, &tokens);
                let length = parse_number(token(at), count, line)? as usize;
                values.clear();
                for i in 0..length {
                    values.push(parse_number(token(at + 1 + i), item, line)?);
                }
                plan.indices(record, &values, &mut indices)?;
                builder.face(&indices, || face_location(record))?;
            }
        }
    }
    Ok(())
}
