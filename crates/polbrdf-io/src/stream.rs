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
//!
//! This file is the reader's dispatcher: it opens a table and hands each chunk to the reader of
//! its format. The parts, whose `use` edges point one way (none uses this file):
//!
//! - `format`: the formats and the extension that names each (uses nothing here);
//! - `chunk`: the chunk type and its bounds (uses nothing here);
//! - `columns`: where a table's geometry and wavelength are, and numeric rows' geometries
//!   (uses `chunk`);
//! - `read_csv`, `read_npy`, `read_arrow`: the chunk reader of each format (use `chunk`,
//!   `columns`);
//! - `encode`: a chunk's rows and results encoded per output format (uses `chunk`);
//! - `writer`: [`ResultWriter`] (uses `format`, `chunk`, `encode`).
//!
//! [`ANGLE_COLUMNS`]: crate::csv_io::ANGLE_COLUMNS
//! [`DIRECTION_COLUMNS`]: crate::csv_io::DIRECTION_COLUMNS
//! [`Output`]: crate::write::Output

mod chunk;
mod columns;
mod encode;
mod format;
#[cfg(feature = "arrow")]
mod read_arrow;
mod read_csv;
mod read_npy;
mod writer;

pub use crate::table::{result_values, Column, Kind, RowResult};
pub use chunk::{
    chunk_rows, Geometries, GeometryChunk, Passthrough, TextRows, CHUNK_CELLS, CHUNK_ROWS,
    CHUNK_TEXT_BYTES,
};
pub use format::Format;
pub use writer::ResultWriter;

use crate::csv_io::CsvReader;
use crate::error::{Error, Result};
use crate::npy::NpyReader;
use columns::{wavelength_column, GeometryColumns, Layout};
#[cfg(not(feature = "arrow"))]
use format::no_arrow;
use std::io::{BufReader, Read};
use std::path::{Path, PathBuf};

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

    /// The reader of a source whose header has been read: checks the columns
    /// ([`GeometryColumns::of`]).
    fn with_src(path: &Path, headers: Vec<String>, src: Src) -> Result<Self> {
        let columns = GeometryColumns::of(&headers, path)?;
        let wavelength = wavelength_column(&headers);
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
        let max = chunk_rows(max, self.headers.len());
        let layout = Layout {
            path: &self.path,
            headers: &self.headers,
            geometry: self.columns,
            wavelength: self.wavelength,
        };
        let chunk = match &mut self.src {
            Src::Csv(r) => Some(read_csv::csv_chunk(r, &layout, max)?),
            Src::Npy(r) => Some(read_npy::npy_chunk(r, &layout, max, &mut self.buf)?),
            #[cfg(feature = "arrow")]
            Src::Arrow(r) => read_arrow::arrow_chunk(r, &layout, max)?,
        };
        match chunk {
            Some(chunk) if !chunk.is_empty() => Ok(Some(chunk)),
            // The end of the table: an empty chunk, or none (Arrow).
            _ => {
                self.done = true;
                Ok(None)
            }
        }
    }
}
