//! The PCD header's lines as read, one slot per keyword, before anything
//! checks what they say; and the error for a malformed one.

use crate::format::FormatError;

/// One header line: its number and the values after its keyword.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Line<'a> {
    pub number: usize,
    pub values: Vec<&'a str>,
}

/// The header lines read so far, one slot per keyword.
#[derive(Default)]
pub(super) struct RawHeader<'a> {
    pub version: Option<Line<'a>>,
    pub fields: Option<Line<'a>>,
    pub size: Option<Line<'a>>,
    pub ty: Option<Line<'a>>,
    pub count: Option<Line<'a>>,
    pub width: Option<Line<'a>>,
    pub height: Option<Line<'a>>,
    pub viewpoint: Option<Line<'a>>,
    pub points: Option<Line<'a>>,
}

impl<'a> RawHeader<'a> {
    /// The slot of `keyword` (`COLUMNS` is the v0.5 spelling of `FIELDS`).
    pub(super) fn slot(&mut self, keyword: &str) -> Option<&mut Option<Line<'a>>> {
        Some(match keyword {
            "VERSION" => &mut self.version,
            "FIELDS" | "COLUMNS" => &mut self.fields,
            "SIZE" => &mut self.size,
            "TYPE" => &mut self.ty,
            "COUNT" => &mut self.count,
            "WIDTH" => &mut self.width,
            "HEIGHT" => &mut self.height,
            "VIEWPOINT" => &mut self.viewpoint,
            "POINTS" => &mut self.points,
            _ => return None,
        })
    }
}

/// The error for header line `line`, saying what is wrong with it.
pub(super) fn malformed(line: usize, reason: String) -> FormatError {
    FormatError::PcdMalformedHeader { line, reason }
}
