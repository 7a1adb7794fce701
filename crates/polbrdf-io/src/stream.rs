//! Streaming geometry tables in and result tables out (`polbrdf eval`): CSV, `.npy` or Arrow
//! IPC (`.arrow`, `.feather`: file format; `.arrows`: stream format; feature `arrow`), chosen
//! by the file's extension, read and written in chunks of rows so memory stays bounded for any
//! number of rows.
//!
//! Input: [`GeometryReader`] gives [`GeometryChunk`]s of validated rows, each with its line
//! (CSV: the physical line; `.npy`, Arrow: the 1-based row) for messages. A row's geometry is
//! its four angles ([`ANGLE_COLUMNS`]) or, in a table with the direction columns
//! ([`DIRECTION_COLUMNS`]) instead, its two direction vectors ([`Geometries`]).
//! Output: [`ResultWriter`] writes the input columns, then `brdf, dolp, aolp_deg, m00 … m33`
//! ([`crate::csv_io::result_columns`]), into an [`Output`] (atomic for a regular file).
//! A `.npy` output holds numbers only: a CSV input column that is not a number is an error
//! naming its line and column.

use crate::csv_io::{
    directions_of, fmt_f64_into, parse_number, result_columns, row_directions, row_geometry,
    row_wavelength, CsvReader, ANGLE_COLUMNS, DIRECTION_COLUMNS, WAVELENGTH_COLUMN,
};
use crate::error::{Error, Result};
use crate::npy::{NpyReader, NpyWriter};
pub use crate::table::{result_values, Column, Kind, RowResult};
use crate::write::Output;
use polbrdf::Geometry;
use std::io::{BufReader, Read, Seek, Write};
use std::path::{Path, PathBuf};

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

/// A table format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Comma-separated text with a header line.
    Csv,
    /// NumPy `.npy` structured array ([`crate::npy`]).
    Npy,
    /// Arrow IPC file format (Feather v2): `.arrow`, `.feather`.
    ArrowFile,
    /// Arrow IPC stream format: `.arrows`.
    ArrowStream,
}

impl Format {
    /// The format a path's extension names (any case): `.npy` is [`Format::Npy`], `.arrow`
    /// and `.feather` [`Format::ArrowFile`], `.arrows` [`Format::ArrowStream`], anything else
    /// (and `-`) CSV.
    pub fn of(path: &Path) -> Format {
        match path.extension().and_then(|e| e.to_str()) {
            Some(e) if e.eq_ignore_ascii_case("npy") => Format::Npy,
            Some(e) if e.eq_ignore_ascii_case("arrow") || e.eq_ignore_ascii_case("feather") => {
                Format::ArrowFile
            }
            Some(e) if e.eq_ignore_ascii_case("arrows") => Format::ArrowStream,
            _ => Format::Csv,
        }
    }

    /// True for the Arrow IPC formats.
    pub fn is_arrow(self) -> bool {
        matches!(self, Format::ArrowFile | Format::ArrowStream)
    }
}

/// The error for an Arrow table in a build without the feature `arrow`.
#[cfg(not(feature = "arrow"))]
fn no_arrow(path: &Path) -> Error {
    Error::File {
        path: path.to_path_buf(),
        message: "this build of polbrdf lacks Arrow support (built without the feature `arrow`); \
                  use CSV or .npy, or rebuild with `--features arrow`"
            .into(),
    }
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
    fn with_capacity(rows: usize, width: usize) -> Self {
        let cells = rows.saturating_mul(width).min(CHUNK_CELLS);
        Self {
            text: String::with_capacity(cells * 4),
            ends: Vec::with_capacity(cells),
            width,
        }
    }

    /// The bytes of field text held.
    fn text_len(&self) -> usize {
        self.text.len()
    }

    /// Appends a record (with `width` fields: the reader checks every record's length).
    fn push(&mut self, r: &crate::csv_io::Record<'_>) {
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
    Angles(Vec<Geometry>),
    /// From the direction columns ([`DIRECTION_COLUMNS`]): `w_i` (toward the source) and
    /// `w_r` (toward the detector) per row, each finite and of a length the core's
    /// `DirectionBatch` accepts; a vector at or below the horizon (`z ≤ 0`) gives a zero pBRDF.
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

/// Which columns of a table hold its geometry, and where.
#[derive(Debug, Clone, Copy)]
enum GeometryColumns {
    Angles([usize; 4]),
    Directions([usize; 6]),
}

// Only the Arrow reader takes the geometry columns by position.
#[cfg(feature = "arrow")]
impl GeometryColumns {
    /// The positions of the geometry columns.
    fn indices(&self) -> &[usize] {
        match self {
            GeometryColumns::Angles(idx) => idx,
            GeometryColumns::Directions(idx) => idx,
        }
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

type Source = Box<dyn Read + Send>;

enum Src {
    Csv(Box<CsvReader<BufReader<Source>>>),
    Npy(NpyReader<BufReader<Source>>),
    #[cfg(feature = "arrow")]
    Arrow(crate::arrow::ArrowReader),
}

/// A geometry table read in chunks (CSV, `.npy` or Arrow by extension; `-` = CSV on
/// standard input).
pub struct GeometryReader {
    path: PathBuf,
    headers: Vec<String>,
    columns: GeometryColumns,
    wavelength: Option<usize>,
    src: Src,
    buf: Vec<f64>,
    done: bool,
}

impl std::fmt::Debug for GeometryReader {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GeometryReader")
            .field("path", &self.path)
            .field("headers", &self.headers)
            .finish_non_exhaustive()
    }
}

impl GeometryReader {
    /// Opens `path` and reads its header (CSV header line, `.npy` header, Arrow schema).
    ///
    /// # Errors
    /// [`Error::Read`]; [`Error::Syntax`] / [`Error::File`] for a malformed header, an empty
    /// file, a repeated or missing column, an Arrow table in a build without Arrow support.
    pub fn open(path: &Path) -> Result<Self> {
        let format = Format::of(path);
        #[cfg(not(feature = "arrow"))]
        if format.is_arrow() {
            return Err(no_arrow(path));
        }
        let file = if path.as_os_str() == "-" {
            None
        } else {
            Some(std::fs::File::open(path).map_err(|source| Error::Read {
                path: path.to_path_buf(),
                source,
            })?)
        };
        #[cfg(feature = "arrow")]
        if let (Format::ArrowFile, Some(f)) = (format, &file) {
            // A regular file is read through its footer; anything else front to back.
            if f.metadata().is_ok_and(|m| m.is_file()) {
                let r = crate::arrow::ArrowReader::file(file.expect("a file"), path)?;
                return Self::with_src(path, r.columns().to_vec(), Src::Arrow(r));
            }
        }
        let src: Source = match file {
            Some(f) => Box::new(f),
            None => Box::new(std::io::stdin()),
        };
        Self::from_reader(src, path, format)
    }

    /// Reads a table of `format` from `src`; `path` is used in messages.
    ///
    /// # Errors
    /// As [`open`](Self::open).
    pub fn from_reader(src: Source, path: &Path, format: Format) -> Result<Self> {
        let (headers, src) = match format {
            Format::Npy => {
                let r = NpyReader::new(BufReader::with_capacity(1 << 16, src), path)?;
                (r.header().columns.clone(), Src::Npy(r))
            }
            Format::Csv => {
                let r = CsvReader::new(BufReader::with_capacity(1 << 16, src), path)?;
                (r.headers().to_vec(), Src::Csv(Box::new(r)))
            }
            #[cfg(feature = "arrow")]
            Format::ArrowFile | Format::ArrowStream => {
                let r = if format == Format::ArrowFile {
                    crate::arrow::ArrowReader::file_sequential(src, path)?
                } else {
                    crate::arrow::ArrowReader::stream(src, path)?
                };
                (r.columns().to_vec(), Src::Arrow(r))
            }
            #[cfg(not(feature = "arrow"))]
            Format::ArrowFile | Format::ArrowStream => return Err(no_arrow(path)),
        };
        Self::with_src(path, headers, src)
    }

    /// The reader of a source whose header has been read: checks the columns. The geometry is
    /// the angle columns, or the direction columns when the table has one of those and not
    /// every angle column; a table with both complete sets is refused (which set would hold?).
    fn with_src(path: &Path, headers: Vec<String>, src: Src) -> Result<Self> {
        let has = |c: &&str| headers.iter().any(|h| h == c);
        let columns = if DIRECTION_COLUMNS.iter().any(has) && !ANGLE_COLUMNS.iter().all(has) {
            let idx = crate::csv_io::check_header(&headers, path, &DIRECTION_COLUMNS)?;
            GeometryColumns::Directions(idx.try_into().expect("six columns"))
        } else {
            let idx = crate::csv_io::check_header(&headers, path, &ANGLE_COLUMNS)?;
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
            GeometryColumns::Angles(idx.try_into().expect("four columns"))
        };
        let wavelength = headers.iter().position(|h| h == WAVELENGTH_COLUMN);
        Ok(Self {
            path: path.to_path_buf(),
            columns,
            headers,
            wavelength,
            src,
            buf: Vec::new(),
            done: false,
        })
    }

    /// The column names.
    pub fn headers(&self) -> &[String] {
        &self.headers
    }

    /// The format read.
    pub fn format(&self) -> Format {
        match self.src {
            Src::Csv(_) => Format::Csv,
            Src::Npy(_) => Format::Npy,
            #[cfg(feature = "arrow")]
            Src::Arrow(_) => Format::of(&self.path),
        }
    }

    /// The kinds of the columns, when the format says them before the first row (`.npy`:
    /// numbers; Arrow: its schema).
    pub fn column_kinds(&self) -> Option<Vec<Kind>> {
        match &self.src {
            Src::Npy(_) => Some(vec![Kind::Number; self.headers.len()]),
            Src::Csv(_) => None,
            #[cfg(feature = "arrow")]
            Src::Arrow(r) => Some(r.kinds().to_vec()),
        }
    }

    /// The number of rows, when the format says it in advance (`.npy`).
    pub fn rows_hint(&self) -> Option<u64> {
        match &self.src {
            Src::Npy(r) => Some(r.header().rows),
            Src::Csv(_) => None,
            #[cfg(feature = "arrow")]
            Src::Arrow(r) => r.rows_hint(),
        }
    }

    /// True when the table has a `wavelength_um` column.
    pub fn has_wavelengths(&self) -> bool {
        self.wavelength.is_some()
    }

    /// The next chunk of at most `max` rows, or `None` at the end. A chunk of a wide table
    /// holds fewer rows: at most [`CHUNK_CELLS`] cells ([`chunk_rows`]) and, for CSV, about
    /// [`CHUNK_TEXT_BYTES`] of text; memory is bounded by the bytes read, never by a row count.
    ///
    /// # Errors
    /// [`Error::Syntax`] (bad CSV or UTF-8, with the line), [`Error::Field`] (a non-number or
    /// an invalid angle or wavelength, with line and column), [`Error::File`] / [`Error::Read`]
    /// for a truncated or unreadable `.npy`.
    pub fn next_chunk(&mut self, max: usize) -> Result<Option<GeometryChunk>> {
        if self.done {
            return Ok(None);
        }
        let path = self.path.clone();
        let columns = self.columns;
        let max = chunk_rows(max, self.headers.len());
        let chunk = match &mut self.src {
            Src::Csv(rdr) => {
                let cap = max.min(CHUNK_ROWS);
                let mut records = TextRows::with_capacity(cap, self.headers.len());
                let mut lines = Vec::with_capacity(cap);
                while lines.len() < max && records.text_len() < CHUNK_TEXT_BYTES {
                    let Some(r) = rdr.next_record()? else {
                        break;
                    };
                    lines.push(r.line);
                    records.push(&r);
                }
                // Parsed in parallel; the first bad row (in file order) is the error.
                use rayon::prelude::*;
                let geometries = match columns {
                    GeometryColumns::Angles(idx) => {
                        let parsed: Vec<Result<Geometry>> = lines
                            .par_iter()
                            .enumerate()
                            .map(|(k, &line)| {
                                row_geometry(&path, line, idx.map(|i| records.field(k, i)))
                            })
                            .collect();
                        Geometries::Angles(parsed.into_iter().collect::<Result<_>>()?)
                    }
                    GeometryColumns::Directions(idx) => {
                        let parsed: Vec<Result<([f64; 3], [f64; 3])>> = lines
                            .par_iter()
                            .enumerate()
                            .map(|(k, &line)| {
                                row_directions(&path, line, idx.map(|i| records.field(k, i)))
                            })
                            .collect();
                        let pairs = parsed.into_iter().collect::<Result<Vec<_>>>()?;
                        let (w_i, w_r) = pairs.into_iter().unzip();
                        Geometries::Directions { w_i, w_r }
                    }
                };
                let wavelengths = match self.wavelength {
                    Some(w) => Some(
                        lines
                            .iter()
                            .enumerate()
                            .map(|(k, &line)| row_wavelength(&path, line, records.field(k, w)))
                            .collect::<Result<Vec<f64>>>()?,
                    ),
                    None => None,
                };
                GeometryChunk {
                    lines,
                    geometries,
                    wavelengths,
                    columns: Passthrough::Text(records),
                }
            }
            Src::Npy(r) => {
                let first = r.rows_read() as usize + 1;
                let cols = self.headers.len();
                self.buf.clear();
                let mut n = 0;
                while n < max {
                    let k = r.read_rows(max - n, &mut self.buf)?;
                    if k == 0 {
                        break;
                    }
                    n += k;
                }
                let lines: Vec<usize> = (first..first + n).collect();
                let mut rows = RowGeometries::new(columns, n);
                let mut wavelengths = self.wavelength.map(|_| Vec::with_capacity(n));
                for (row, &line) in self.buf.chunks_exact(cols).zip(&lines) {
                    rows.push(&path, line, |i| row[i])?;
                    if let (Some(w), Some(out)) = (self.wavelength, wavelengths.as_mut()) {
                        out.push(checked_wavelength(&path, line, row[w])?);
                    }
                }
                GeometryChunk {
                    lines,
                    geometries: rows.finish(),
                    wavelengths,
                    columns: Passthrough::Numbers(std::mem::take(&mut self.buf)),
                }
            }
            #[cfg(feature = "arrow")]
            Src::Arrow(r) => {
                let first = r.rows_read() as usize + 1;
                let Some(cols) = r.next_rows(max)? else {
                    self.done = true;
                    return Ok(None);
                };
                let n = match cols.first() {
                    Some(Column::Numbers(v)) => v.len(),
                    Some(Column::Text(v)) => v.len(),
                    None => 0,
                };
                let lines: Vec<usize> = (first..first + n).collect();
                // The angle and wavelength columns must be numbers.
                let number = |i: usize| -> Result<&[f64]> {
                    match &cols[i] {
                        Column::Numbers(v) => Ok(v),
                        Column::Text(v) => Err(Error::Field {
                            path: path.clone(),
                            line: first,
                            field: self.headers[i].clone(),
                            message: format!(
                                "a text column (`{}`); this column must hold numbers",
                                v.first().map(String::as_str).unwrap_or("")
                            ),
                        }),
                    }
                };
                // The geometry columns' numbers, by column index (the others left empty).
                let mut numbers: Vec<&[f64]> = vec![&[]; cols.len()];
                for &i in columns.indices() {
                    numbers[i] = number(i)?;
                }
                let mut rows = RowGeometries::new(columns, n);
                for (k, &line) in lines.iter().enumerate() {
                    rows.push(&path, line, |i| numbers[i][k])?;
                }
                let geometries = rows.finish();
                let wavelengths = match self.wavelength {
                    Some(w) => Some(
                        number(w)?
                            .iter()
                            .zip(&lines)
                            .map(|(&v, &line)| checked_wavelength(&path, line, v))
                            .collect::<Result<Vec<f64>>>()?,
                    ),
                    None => None,
                };
                GeometryChunk {
                    lines,
                    geometries,
                    wavelengths,
                    columns: Passthrough::Columns(cols),
                }
            }
        };
        if chunk.is_empty() {
            self.done = true;
            return Ok(None);
        }
        Ok(Some(chunk))
    }
}

/// The geometries of a chunk being read row by row (`.npy` and Arrow input), with the
/// columns they come from.
enum RowGeometries {
    Angles([usize; 4], Vec<Geometry>),
    Directions([usize; 6], Vec<[f64; 3]>, Vec<[f64; 3]>),
}

impl RowGeometries {
    /// Room for `n` rows of the kind `columns` reads.
    fn new(columns: GeometryColumns, n: usize) -> Self {
        match columns {
            GeometryColumns::Angles(idx) => RowGeometries::Angles(idx, Vec::with_capacity(n)),
            GeometryColumns::Directions(idx) => {
                RowGeometries::Directions(idx, Vec::with_capacity(n), Vec::with_capacity(n))
            }
        }
    }

    /// Appends the row at `line` whose value in column `i` is `value(i)`, with the same checks
    /// and messages as a CSV row's.
    fn push(&mut self, path: &Path, line: usize, value: impl Fn(usize) -> f64) -> Result<()> {
        match self {
            RowGeometries::Angles(idx, g) => g.push(numeric_geometry(path, line, idx.map(value))?),
            RowGeometries::Directions(idx, w_i, w_r) => {
                let (i, r) = directions_of(path, line, idx.map(value))?;
                w_i.push(i);
                w_r.push(r);
            }
        }
        Ok(())
    }

    fn finish(self) -> Geometries {
        match self {
            RowGeometries::Angles(_, g) => Geometries::Angles(g),
            RowGeometries::Directions(_, w_i, w_r) => Geometries::Directions { w_i, w_r },
        }
    }
}

/// A geometry from four angles in degrees read from a `.npy` row (same checks and messages as
/// a CSV row's).
fn numeric_geometry(path: &Path, line: usize, deg: [f64; 4]) -> Result<Geometry> {
    crate::csv_io::geometry_of_degrees(path, line, deg)
}

fn checked_wavelength(path: &Path, line: usize, v: f64) -> Result<f64> {
    crate::csv_io::check_wavelength(path, line, v)
}

enum Sink {
    Csv {
        out: Output,
    },
    /// Into the output directly (known row count, or a seekable output patched at the end).
    Npy(NpyWriter<Output>),
    /// Into an anonymous spool file, copied to the (unseekable) output at the end.
    NpySpool {
        w: NpyWriter<BufWriterFile>,
        out: Output,
    },
    /// Arrow IPC, its schema fixed by the first chunk (or by [`ResultWriter::column_kinds`]).
    #[cfg(feature = "arrow")]
    Arrow(ArrowSink),
}

/// An Arrow output: waiting for its schema, then open.
#[cfg(feature = "arrow")]
enum ArrowSink {
    Pending {
        out: Output,
        stream: bool,
        kinds: Option<Vec<Kind>>,
    },
    Open {
        w: Box<crate::arrow::ArrowWriter<Output>>,
        kinds: Vec<Kind>,
        shown: PathBuf,
    },
    /// Only while switching from `Pending` to `Open`.
    Gone,
}

type BufWriterFile = std::io::BufWriter<std::fs::File>;

/// The result table of `eval`, written chunk by chunk into an [`Output`].
pub struct ResultWriter {
    sink: Sink,
    input: PathBuf,
    headers: Vec<String>,
    row: Vec<f64>,
}

impl std::fmt::Debug for ResultWriter {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ResultWriter")
            .field("input", &self.input)
            .finish_non_exhaustive()
    }
}

impl ResultWriter {
    /// Starts the result table in `out` (format from `out`'s name): the input's `headers`
    /// then the result columns; `rows` is the row count when known.
    ///
    /// # Errors
    /// [`Error::File`] (naming `input`) when an input column has the name of an output column;
    /// [`Error::Write`].
    pub fn new(
        mut out: Output,
        input: &Path,
        headers: &[String],
        rows: Option<u64>,
    ) -> Result<Self> {
        let extra = result_columns();
        if let Some(clash) = headers.iter().find(|h| extra.contains(h)) {
            return Err(Error::File {
                path: input.to_path_buf(),
                message: format!(
                    "input column `{clash}` has the name of an output column; rename it"
                ),
            });
        }
        let all: Vec<String> = headers.iter().chain(&extra).cloned().collect();
        let npy_err = |out: &Output, e: std::io::Error| {
            if e.kind() == std::io::ErrorKind::InvalidInput {
                Error::File {
                    path: out.path().to_path_buf(),
                    message: format!("cannot write a .npy table: {e}"),
                }
            } else {
                out.error(e)
            }
        };
        let sink = match Format::of(out.path()) {
            #[cfg(feature = "arrow")]
            f @ (Format::ArrowFile | Format::ArrowStream) => Sink::Arrow(ArrowSink::Pending {
                out,
                stream: f == Format::ArrowStream,
                kinds: None,
            }),
            #[cfg(not(feature = "arrow"))]
            Format::ArrowFile | Format::ArrowStream => return Err(no_arrow(out.path())),
            Format::Csv => {
                let mut line = Vec::new();
                {
                    let mut w = csv::Writer::from_writer(&mut line);
                    w.write_record(&all).map_err(|e| out.error(e.into()))?;
                    w.flush().map_err(|e| out.error(e))?;
                }
                out.write_all(&line).map_err(|e| out.error(e))?;
                Sink::Csv { out }
            }
            Format::Npy => match rows {
                Some(n) => {
                    if let Err(e) = crate::npy::check_columns(&all) {
                        return Err(npy_err(&out, e));
                    }
                    let shown = out.path().to_path_buf();
                    Sink::Npy(NpyWriter::new(out, &all, n).map_err(|source| Error::Write {
                        path: shown,
                        source,
                    })?)
                }
                None if out.is_seekable() => {
                    if let Err(e) = crate::npy::check_columns(&all) {
                        return Err(npy_err(&out, e));
                    }
                    let shown = out.path().to_path_buf();
                    Sink::Npy(NpyWriter::new_patchable(out, &all).map_err(|source| {
                        Error::Write {
                            path: shown,
                            source,
                        }
                    })?)
                }
                None => {
                    if let Err(e) = crate::npy::check_columns(&all) {
                        return Err(npy_err(&out, e));
                    }
                    let spool = tempfile::tempfile().map_err(|e| out.error(e))?;
                    let w = NpyWriter::new_patchable(std::io::BufWriter::new(spool), &all)
                        .map_err(|e| out.error(e))?;
                    Sink::NpySpool { w, out }
                }
            },
        };
        Ok(Self {
            sink,
            input: input.to_path_buf(),
            headers: headers.to_vec(),
            row: Vec::new(),
        })
    }

    /// Declares the kinds of the input columns before the first chunk, when the input's
    /// schema says them (Arrow input): an Arrow output then has that schema even without rows.
    /// Other outputs ignore it.
    pub fn column_kinds(&mut self, kinds: Vec<Kind>) {
        #[cfg(feature = "arrow")]
        if let Sink::Arrow(ArrowSink::Pending { kinds: k, .. }) = &mut self.sink {
            *k = Some(kinds);
        }
        #[cfg(not(feature = "arrow"))]
        let _ = kinds;
    }

    /// The output's name.
    fn shown(&self) -> PathBuf {
        match &self.sink {
            Sink::Csv { out, .. } | Sink::NpySpool { out, .. } => out.path().to_path_buf(),
            Sink::Npy(w) => w.get_ref().path().to_path_buf(),
            #[cfg(feature = "arrow")]
            Sink::Arrow(ArrowSink::Pending { out, .. }) => out.path().to_path_buf(),
            #[cfg(feature = "arrow")]
            Sink::Arrow(ArrowSink::Open { shown, .. }) => shown.clone(),
            #[cfg(feature = "arrow")]
            Sink::Arrow(ArrowSink::Gone) => PathBuf::new(),
        }
    }

    /// Writes one chunk's rows with their results ([`RowResult`], one per row).
    ///
    /// # Errors
    /// [`Error::Write`]; [`Error::Field`] naming the input's line and column when a `.npy`
    /// output is given a CSV column that is not a number.
    pub fn write_chunk(&mut self, chunk: &GeometryChunk, pbrdf: &[RowResult]) -> Result<()> {
        let shown = self.shown();
        let werr = |source| Error::Write {
            path: shown.clone(),
            source,
        };
        let cols = self.headers.len();
        match &mut self.sink {
            Sink::Csv { out } => {
                // Rows formatted in parallel, in blocks, written in order.
                use rayon::prelude::*;
                const BLOCK: usize = 2048;
                let blocks: Vec<Vec<u8>> = pbrdf
                    .par_chunks(BLOCK)
                    .enumerate()
                    .map(|(b, fs)| {
                        let mut buf = Vec::with_capacity(fs.len() * 400);
                        for (j, f) in fs.iter().enumerate() {
                            csv_row(&mut buf, &chunk.columns, b * BLOCK + j, cols, f);
                        }
                        buf
                    })
                    .collect();
                for block in &blocks {
                    out.write_all(block).map_err(werr)?;
                }
                Ok(())
            }
            Sink::Npy(w) => {
                fill_npy_rows(&mut self.row, chunk, pbrdf, &self.headers, &self.input)?;
                w.write_rows(&self.row).map_err(werr)
            }
            Sink::NpySpool { w, .. } => {
                fill_npy_rows(&mut self.row, chunk, pbrdf, &self.headers, &self.input)?;
                w.write_rows(&self.row).map_err(werr)
            }
            #[cfg(feature = "arrow")]
            Sink::Arrow(sink) => {
                if let ArrowSink::Pending { kinds, .. } = sink {
                    let kinds = kinds
                        .take()
                        .unwrap_or_else(|| chunk_kinds(&chunk.columns, cols, &self.input, chunk));
                    sink.open(kinds, &self.headers)?;
                }
                let ArrowSink::Open { w, kinds, shown } = sink else {
                    unreachable!("opened above")
                };
                let columns = arrow_columns(chunk, pbrdf, kinds, &self.headers, &self.input)?;
                w.write_batch(columns)
                    .map_err(|e| crate::arrow::write_err(shown, e))
            }
        }
    }

    /// Ends the table and commits the output.
    ///
    /// # Errors
    /// [`Error::Write`]; then a regular output is left as it was.
    pub fn finish(self) -> Result<()> {
        match self.sink {
            Sink::Csv { out, .. } => out.commit(),
            Sink::Npy(w) => {
                let shown = w.get_ref().path().to_path_buf();
                let seekable = w.get_ref().is_seekable();
                let result = if w.is_patchable() && seekable {
                    w.finish_patched()
                } else {
                    w.finish()
                };
                result
                    .map_err(|source| Error::Write {
                        path: shown,
                        source,
                    })?
                    .commit()
            }
            Sink::NpySpool { w, mut out } => {
                let spool = w.finish_patched().map_err(|e| out.error(e))?;
                let mut f = spool.into_inner().map_err(|e| out.error(e.into_error()))?;
                f.rewind().map_err(|e| out.error(e))?;
                std::io::copy(&mut f, &mut out).map_err(|e| out.error(e))?;
                out.commit()
            }
            #[cfg(feature = "arrow")]
            Sink::Arrow(mut sink) => {
                if let ArrowSink::Pending { kinds, .. } = &mut sink {
                    let kinds = kinds
                        .take()
                        .unwrap_or_else(|| vec![Kind::Number; self.headers.len()]);
                    sink.open(kinds, &self.headers)?;
                }
                let ArrowSink::Open { w, shown, .. } = sink else {
                    unreachable!("opened above")
                };
                w.finish()
                    .map_err(|e| crate::arrow::write_err(&shown, e))?
                    .commit()
            }
        }
    }
}

#[cfg(feature = "arrow")]
impl ArrowSink {
    /// Writes the schema: the input columns of `kinds`, then the result columns (Float64).
    ///
    /// # Errors
    /// [`Error::Write`] / [`Error::File`] naming the output.
    fn open(&mut self, kinds: Vec<Kind>, headers: &[String]) -> Result<()> {
        let ArrowSink::Pending { out, stream, .. } = std::mem::replace(self, ArrowSink::Gone)
        else {
            unreachable!("open once")
        };
        let shown = out.path().to_path_buf();
        let schema: Vec<(String, Kind)> = headers
            .iter()
            .cloned()
            .zip(kinds.iter().copied())
            .chain(result_columns().into_iter().map(|c| (c, Kind::Number)))
            .collect();
        let w = crate::arrow::ArrowWriter::new(out, &schema, stream)
            .map_err(|e| crate::arrow::write_err(&shown, e))?;
        *self = ArrowSink::Open {
            w: Box::new(w),
            kinds,
            shown,
        };
        Ok(())
    }
}

/// The kinds of a chunk's input columns for an Arrow output: `.npy` and Arrow input say them;
/// a CSV column is numbers when every field of the first chunk is a number, else text.
#[cfg(feature = "arrow")]
fn chunk_kinds(
    columns: &Passthrough,
    cols: usize,
    input: &Path,
    chunk: &GeometryChunk,
) -> Vec<Kind> {
    match columns {
        Passthrough::Numbers(_) => vec![Kind::Number; cols],
        Passthrough::Columns(c) => c.iter().map(Column::kind).collect(),
        Passthrough::Text(recs) => (0..cols)
            .map(|i| {
                let numbers = (0..recs.len())
                    .all(|k| parse_number(input, chunk.lines[k], "", recs.field(k, i)).is_ok());
                if numbers {
                    Kind::Number
                } else {
                    Kind::Text
                }
            })
            .collect(),
    }
}

/// A chunk's columns for an Arrow output: the input columns as `kinds` says, then the 19
/// result columns.
///
/// # Errors
/// [`Error::Field`] naming the input's line and column when a CSV column that was numbers in
/// the first chunk holds something else.
#[cfg(feature = "arrow")]
fn arrow_columns(
    chunk: &GeometryChunk,
    pbrdf: &[RowResult],
    kinds: &[Kind],
    headers: &[String],
    input: &Path,
) -> Result<Vec<Column>> {
    let n = pbrdf.len();
    let cols = headers.len();
    let mut out = Vec::with_capacity(cols + 19);
    for (i, (kind, name)) in kinds.iter().zip(headers).enumerate() {
        let c = match (&chunk.columns, kind) {
            (Passthrough::Numbers(v), _) => {
                Column::Numbers((0..n).map(|k| v[k * cols + i]).collect())
            }
            (Passthrough::Columns(c), _) => c[i].clone(),
            (Passthrough::Text(recs), Kind::Text) => {
                Column::Text((0..n).map(|k| recs.field(k, i).to_string()).collect())
            }
            (Passthrough::Text(recs), Kind::Number) => Column::Numbers(
                (0..n)
                    .map(|k| {
                        output_number(
                            input,
                            chunk.lines[k],
                            name,
                            recs.field(k, i),
                            &format!(
                                "the column held numbers in the first chunk of rows read (up to \
                                 {CHUNK_ROWS}; fewer in a wide table), so the Arrow output's \
                                 column is Float64"
                            ),
                        )
                    })
                    .collect::<Result<Vec<f64>>>()?,
            ),
        };
        out.push(c);
    }
    let mut results: Vec<Vec<f64>> = (0..19).map(|_| Vec::with_capacity(n)).collect();
    for f in pbrdf {
        for (col, v) in results.iter_mut().zip(result_values(f)) {
            col.push(v);
        }
    }
    out.extend(results.into_iter().map(Column::Numbers));
    Ok(out)
}

/// A passed-through CSV field parsed as a number for a numeric output; an error says `why` the
/// output needs a number.
fn output_number(input: &Path, line: usize, name: &str, text: &str, why: &str) -> Result<f64> {
    parse_number(input, line, name, text).map_err(|e| match e {
        Error::Field {
            path,
            line,
            field,
            message,
        } => Error::Field {
            path,
            line,
            field,
            message: format!("{message} ({why})"),
        },
        other => other,
    })
}

/// One CSV row of the result table: row `k`'s input columns, then its 19 result values.
fn csv_row(line: &mut Vec<u8>, columns: &Passthrough, k: usize, cols: usize, f: &RowResult) {
    match columns {
        Passthrough::Text(recs) => {
            for field in recs.row(k) {
                push_csv_field(line, field);
                line.push(b',');
            }
        }
        Passthrough::Numbers(v) => {
            for x in &v[k * cols..(k + 1) * cols] {
                fmt_f64_into(*x, line);
                line.push(b',');
            }
        }
        Passthrough::Columns(c) => {
            for col in c {
                match col {
                    Column::Numbers(v) => fmt_f64_into(v[k], line),
                    Column::Text(v) => push_csv_field(line, &v[k]),
                }
                line.push(b',');
            }
        }
    }
    for (i, x) in result_values(f).iter().enumerate() {
        if i > 0 {
            line.push(b',');
        }
        fmt_f64_into(*x, line);
    }
    line.push(b'\n');
}

/// A CSV field, quoted where CSV needs it (as the csv crate's writer quotes).
fn push_csv_field(line: &mut Vec<u8>, field: &str) {
    if field
        .bytes()
        .any(|b| matches!(b, b',' | b'"' | b'\n' | b'\r'))
    {
        line.push(b'"');
        for b in field.bytes() {
            if b == b'"' {
                line.push(b'"');
            }
            line.push(b);
        }
        line.push(b'"');
    } else {
        line.extend_from_slice(field.as_bytes());
    }
}

/// A chunk's rows as numbers, row-major, into `row`: the input columns, then the results.
///
/// # Errors
/// [`Error::Field`] naming the input's line and column for a CSV field that is not a number.
fn fill_npy_rows(
    row: &mut Vec<f64>,
    chunk: &GeometryChunk,
    pbrdf: &[RowResult],
    headers: &[String],
    input: &Path,
) -> Result<()> {
    let cols = headers.len();
    row.clear();
    for (k, f) in pbrdf.iter().enumerate() {
        match &chunk.columns {
            Passthrough::Text(recs) => {
                for (field, name) in recs.row(k).zip(headers) {
                    let v = output_number(
                        input,
                        chunk.lines[k],
                        name,
                        field,
                        "a .npy output holds numbers only",
                    )?;
                    row.push(v);
                }
            }
            Passthrough::Numbers(v) => row.extend_from_slice(&v[k * cols..(k + 1) * cols]),
            Passthrough::Columns(c) => {
                for (col, name) in c.iter().zip(headers) {
                    match col {
                        Column::Numbers(v) => row.push(v[k]),
                        Column::Text(_) => {
                            return Err(Error::Field {
                                path: input.to_path_buf(),
                                line: chunk.lines[k],
                                field: name.clone(),
                                message: "a text column (a .npy output holds numbers only)".into(),
                            })
                        }
                    }
                }
            }
        }
        row.extend_from_slice(&result_values(f));
    }
    Ok(())
}
