//! Where a table's geometry and wavelength are (chosen from its header), and the geometries of
//! numeric rows (`.npy`, Arrow) checked as a CSV row's are.

use super::chunk::Geometries;
use crate::csv_io::{
    check_header, directions_of, geometry_of_degrees, ANGLE_COLUMNS, DIRECTION_COLUMNS,
    WAVELENGTH_COLUMN,
};
use crate::error::{Error, Result};
use polbrdf::Geometry;
use std::path::Path;

/// Which columns of a table hold its geometry, and where.
#[derive(Debug, Clone, Copy)]
pub(super) enum GeometryColumns {
    /// The angle columns ([`ANGLE_COLUMNS`] order).
    Angles([usize; 4]),
    /// The direction columns ([`DIRECTION_COLUMNS`] order).
    Directions([usize; 6]),
}

impl GeometryColumns {
    /// The geometry columns of a table with these `headers` (`path` names it in messages): the
    /// angle columns, or the direction columns when the table has one of those and not every
    /// angle column; a table with both complete sets is refused (which set would hold?).
    ///
    /// # Errors
    /// [`Error::File`] / [`Error::Syntax`] for an empty header, a repeated or missing column,
    /// or both complete sets.
    pub(super) fn of(headers: &[String], path: &Path) -> Result<Self> {
        let has = |c: &&str| headers.iter().any(|h| h == c);
        if DIRECTION_COLUMNS.iter().any(has) && !ANGLE_COLUMNS.iter().all(has) {
            let idx = check_header(headers, path, &DIRECTION_COLUMNS)?;
            return Ok(GeometryColumns::Directions(
                idx.try_into().expect("six columns"),
            ));
        }
        let idx = check_header(headers, path, &ANGLE_COLUMNS)?;
        if DIRECTION_COLUMNS.iter().all(has) {
            return Err(Error::File {
                path: path.to_path_buf(),
                message: format!(
                    "both the angle columns ({}) and the direction columns ({}): give one \
                     geometry per row, as angles or as direction vectors",
                    ANGLE_COLUMNS.join(", "),
                    DIRECTION_COLUMNS.join(", ")
                ),
            });
        }
        Ok(GeometryColumns::Angles(
            idx.try_into().expect("four columns"),
        ))
    }

    /// The positions of the geometry columns (only the Arrow reader takes them by position).
    #[cfg(feature = "arrow")]
    pub(super) fn indices(&self) -> &[usize] {
        match self {
            GeometryColumns::Angles(idx) => idx,
            GeometryColumns::Directions(idx) => idx,
        }
    }
}

/// The position of the `wavelength_um` column in `headers`, if it has one.
pub(super) fn wavelength_column(headers: &[String]) -> Option<usize> {
    headers.iter().position(|h| h == WAVELENGTH_COLUMN)
}

/// What a chunk reader needs of its table's header: the table's name for messages, its column
/// names, and where its geometry and wavelength are.
#[derive(Debug, Clone, Copy)]
pub(super) struct Layout<'a> {
    /// The table's name in messages.
    pub(super) path: &'a Path,
    /// The column names.
    pub(super) headers: &'a [String],
    /// The geometry columns.
    pub(super) geometry: GeometryColumns,
    /// The `wavelength_um` column, if any.
    pub(super) wavelength: Option<usize>,
}

/// The geometries of a chunk being read row by row (`.npy` and Arrow input), with the
/// columns they come from.
pub(super) enum RowGeometries {
    Angles([usize; 4], Vec<Geometry>),
    Directions([usize; 6], Vec<[f64; 3]>, Vec<[f64; 3]>),
}

impl RowGeometries {
    /// Room for `n` rows of the kind `columns` reads.
    pub(super) fn new(columns: GeometryColumns, n: usize) -> Self {
        match columns {
            GeometryColumns::Angles(idx) => RowGeometries::Angles(idx, Vec::with_capacity(n)),
            GeometryColumns::Directions(idx) => {
                RowGeometries::Directions(idx, Vec::with_capacity(n), Vec::with_capacity(n))
            }
        }
    }

    /// Appends the row at `line` whose value in column `i` is `value(i)`, with the same checks
    /// and messages as a CSV row's.
    pub(super) fn push(
        &mut self,
        path: &Path,
        line: usize,
        value: impl Fn(usize) -> f64,
    ) -> Result<()> {
        match self {
            RowGeometries::Angles(idx, g) => {
                g.push(geometry_of_degrees(path, line, idx.map(value))?)
            }
            RowGeometries::Directions(idx, w_i, w_r) => {
                let (i, r) = directions_of(path, line, idx.map(value))?;
                w_i.push(i);
                w_r.push(r);
            }
        }
        Ok(())
    }

    /// The geometries read.
    pub(super) fn finish(self) -> Geometries {
        match self {
            RowGeometries::Angles(_, g) => Geometries::Angles(g),
            RowGeometries::Directions(_, w_i, w_r) => Geometries::Directions { w_i, w_r },
        }
    }
}
