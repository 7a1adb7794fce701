//! The chunk type: a bounded number of validated rows, with their geometries, wavelengths and
//! the input columns passed through to the output, and the bounds of a chunk.

use crate::table::Column;
use polbrdf::Geometry;

/// Rows per chunk, at most (a narrow table's chunk).
pub const CHUNK_ROWS: usize = 1 << 16;

/// Cells (rows × columns) per chunk, at most: a chunk of a wide table holds fewer rows, so
/// that its memory is bounded by bytes, not by rows (16 MiB of numbers, or of CSV field ends;
/// a table of 10⁵ columns is read 20 rows at a time). A chunk holds at least one row.
pub const CHUNK_CELLS: usize = 1 << 21;

/// Bytes of CSV field text per chunk, at most (the chunk ends after the row that reaches it;
/// a row is at most [`crate::csv_io::MAX_LINE_BYTES`]).
pub const CHUNK_TEXT_BYTES: usize = 1 << 24;

/// The most rows of a chunk of a table `width` columns wide when `max` are asked for: at most
/// [`CHUNK_CELLS`] cells, but at least one row (for `max ≥ 1`).
pub fn chunk_rows(max: usize, width: usize) -> usize {
    max.min((CHUNK_CELLS / width.max(1)).max(1))
}

/// The CSV fields of a chunk's rows in one text buffer (no allocation per row).
#[derive(Debug, Clone, Default)]
pub struct TextRows {
    text: String,
    /// End of each field in `text`; row `k`'s fields are `ends[k·width .. (k+1)·width]`.
    ends: Vec<usize>,
    width: usize,
}

impl TextRows {
    /// Room for `rows` rows of `width` fields ([`chunk_rows`] bounds the product).
    pub(super) fn with_capacity(rows: usize, width: usize) -> Self {
        let cells = rows.saturating_mul(width).min(CHUNK_CELLS);
        Self {
            text: String::with_capacity(cells * 4),
            ends: Vec::with_capacity(cells),
            width,
        }
    }

    /// The bytes of field text held.
    pub(super) fn text_len(&self) -> usize {
        self.text.len()
    }

    /// Appends a record (with `width` fields: the reader checks every record's length).
    pub(super) fn push(&mut self, r: &crate::csv_io::Record<'_>) {
        debug_assert_eq!(r.len(), self.width, "record length");
        for f in r.iter() {
            self.text.push_str(f);
            self.ends.push(self.text.len());
        }
    }

    /// The number of rows.
    pub fn len(&self) -> usize {
        self.ends.len().checked_div(self.width).unwrap_or(0)
    }

    /// True without rows.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Field `i` of row `k`.
    pub fn field(&self, k: usize, i: usize) -> &str {
        let n = k * self.width + i;
        let start = if n == 0 { 0 } else { self.ends[n - 1] };
        &self.text[start..self.ends[n]]
    }

    /// The fields of row `k`, in order.
    pub fn row(&self, k: usize) -> impl Iterator<Item = &str> + '_ {
        (0..self.width).map(move |i| self.field(k, i))
    }
}

/// The input columns passed through to the output, for a chunk's rows.
#[derive(Debug, Clone)]
pub enum Passthrough {
    /// CSV fields as written.
    Text(TextRows),
    /// Numbers, row-major (`.npy` input).
    Numbers(Vec<f64>),
    /// Columns of numbers or text (Arrow input).
    Columns(Vec<Column>),
}

/// The geometries of a chunk's rows, as the table gives them.
#[derive(Debug, Clone, PartialEq)]
pub enum Geometries {
    /// From the angle columns ([`ANGLE_COLUMNS`], degrees).
    ///
    /// [`ANGLE_COLUMNS`]: crate::csv_io::ANGLE_COLUMNS
    Angles(Vec<Geometry>),
    /// From the direction columns ([`DIRECTION_COLUMNS`]): `w_i` (toward the source) and
    /// `w_r` (toward the detector) per row, each finite and of a length the core's
    /// `DirectionBatch` accepts; a vector at or below the horizon (`z ≤ 0`) gives a zero pBRDF.
    ///
    /// [`DIRECTION_COLUMNS`]: crate::csv_io::DIRECTION_COLUMNS
    Directions {
        /// Toward the source.
        w_i: Vec<[f64; 3]>,
        /// Toward the detector.
        w_r: Vec<[f64; 3]>,
    },
}

impl Geometries {
    /// The number of rows.
    pub fn len(&self) -> usize {
        match self {
            Geometries::Angles(g) => g.len(),
            Geometries::Directions { w_i, .. } => w_i.len(),
        }
    }

    /// True without rows.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// A chunk of validated rows.
#[derive(Debug, Clone)]
pub struct GeometryChunk {
    /// Each row's line (CSV) or 1-based row (`.npy`, Arrow).
    pub lines: Vec<usize>,
    /// Each row's geometry.
    pub geometries: Geometries,
    /// Each row's wavelength (µm) when the input has a `wavelength_um` column.
    pub wavelengths: Option<Vec<f64>>,
    /// Every input column of every row.
    pub columns: Passthrough,
}

impl GeometryChunk {
    /// The number of rows.
    pub fn len(&self) -> usize {
        self.geometries.len()
    }

    /// True when the chunk has no row.
    pub fn is_empty(&self) -> bool {
        self.geometries.is_empty()
    }
}
