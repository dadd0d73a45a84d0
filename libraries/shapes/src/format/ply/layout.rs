//! Where the coordinates and the intensity sit in the `vertex` element.

use super::header::{Element, Header, PropertyKind};
use crate::format::scalar::ScalarType;
use crate::format::FormatError;

/// Property names accepted as per-point intensity (ASCII case-insensitive;
/// `scalar_intensity` is how CloudCompare names its scalar fields).
const INTENSITY_NAMES: [&str; 2] = ["intensity", "scalar_intensity"];

/// One wanted scalar property: its index in the element and its type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Slot {
    pub index: usize,
    pub ty: ScalarType,
}

/// The `vertex` element and the slots of x, y, z and the optional intensity.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct VertexLayout {
    /// Index of the vertex element among all elements.
    pub element: usize,
    pub xyz: [Slot; 3],
    pub intensity: Option<Slot>,
}

impl VertexLayout {
    pub fn of(header: &Header) -> Result<Self, FormatError> {
        let element = header
            .elements
            .iter()
            .position(|e| e.name == "vertex")
            .ok_or(FormatError::PlyNoVertexElement)?;
        let vertex = &header.elements[element];
        let coordinate = |axis: char| {
            slot(vertex, &axis.to_string()).ok_or(FormatError::PlyMissingCoordinate { axis })
        };
        let xyz = [coordinate('x')?, coordinate('y')?, coordinate('z')?];
        let intensity = INTENSITY_NAMES.iter().find_map(|name| slot(vertex, name));
        Ok(Self {
            element,
            xyz,
            intensity,
        })
    }

    /// The slots to extract, x, y, z first, then the intensity if present.
    pub fn slots(&self) -> impl Iterator<Item = Slot> + '_ {
        self.xyz.iter().copied().chain(self.intensity)
    }
}

fn slot(element: &Element, name: &str) -> Option<Slot> {
    let index = element.scalar_property(name)?;
    match element.properties[index].kind {
        PropertyKind::Scalar(ty) => Some(Slot { index, ty }),
        PropertyKind::List { .. } => None,
    }
}
