//! Streaming geometry tables in and result tables out (`polbrdf eval`): CSV or `.npy`, chosen
//! by the file's extension, read and written in chunks of rows so memory stays bounded for any
//! number of rows.
//!
//! Input: [`GeometryReader`] gives [`GeometryChunk`]s of validated rows, each with its line
//! (CSV: the physical line; `.npy`: the 1-based row) for messages. Output: [`ResultWriter`]
//! writes the input columns, then `brdf, dolp, aolp_deg, m00 … m33`
//! ([`crate::csv_io::result_columns`]), into an [`Output`] (atomic for a regular file).
//! A `.npy` output holds numbers only: a CSV input column that is not a number is an error
//! naming its line and column.

use crate::csv_io::{
    fmt_f64_into, parse_number, result_columns, row_geometry, row_wavelength, CsvReader,
    ANGLE_COLUMNS, WAVELENGTH_COLUMN,
};
use crate::error::{Error, Result};
use crate::npy::{NpyReader, NpyWriter};
use crate::write::Output;
use polbrdf::{Geometry, Mueller};
use std::io::{BufReader, Read, Seek, Write};
use std::path::{Path, PathBuf};

/// Rows per chunk.
pub const CHUNK_ROWS: usize = 1 << 16;

/// A table format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Comma-separated text with a header line.
    Csv,
    /// NumPy `.npy` structured array ([`crate::npy`]).
    Npy,
}

impl Format {
    /// The format a path's extension names: `.npy` (any case) is [`Format::Npy`], anything
    /// else (and `-`) CSV.
    pub fn of(path: &Path) -> Format {
        match path.extension().and_then(|e| e.to_str()) {
            Some(e) if e.eq_ignore_ascii_case("npy") => Format::Npy,
            _ => Format::Csv,
        }
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
    fn with_capacity(rows: usize, width: usize) -> Self {
        Self {
            text: String::with_capacity(rows * width * 8),
            ends: Vec::with_capacity(rows * width),
            width,
        }
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
}

/// A chunk of validated rows.
#[derive(Debug, Clone)]
pub struct GeometryChunk {
    /// Each row's line (CSV) or 1-based row (`.npy`).
    pub lines: Vec<usize>,
    /// Each row's geometry.
    pub geometries: Vec<Geometry>,
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
}

/// A geometry table read in chunks (CSV or `.npy` by extension; `-` = CSV on standard
/// input).
pub struct GeometryReader {
    path: PathBuf,
    headers: Vec<String>,
    angles: [usize; 4],
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
    /// Opens `path` and reads its header (CSV header line, or `.npy` header).
    ///
    /// # Errors
    /// [`Error::Read`]; [`Error::Syntax`] / [`Error::File`] for a malformed header, an empty
    /// file, a repeated or missing column.
    pub fn open(path: &Path) -> Result<Self> {
        let src: Source = if path.as_os_str() == "-" {
            Box::new(std::io::stdin())
        } else {
            Box::new(std::fs::File::open(path).map_err(|source| Error::Read {
                path: path.to_path_buf(),
                source,
            })?)
        };
        Self::from_reader(src, path, Format::of(path))
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
        };
        let angles = crate::csv_io::check_header(&headers, path, &ANGLE_COLUMNS)?;
        let wavelength = headers.iter().position(|h| h == WAVELENGTH_COLUMN);
        Ok(Self {
            path: path.to_path_buf(),
            angles: angles.try_into().expect("four columns"),
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
        }
    }

    /// The number of rows, when the format says it in advance (`.npy`).
    pub fn rows_hint(&self) -> Option<u64> {
        match &self.src {
            Src::Npy(r) => Some(r.header().rows),
            Src::Csv(_) => None,
        }
    }

    /// True when the table has a `wavelength_um` column.
    pub fn has_wavelengths(&self) -> bool {
        self.wavelength.is_some()
    }

    /// The next chunk of at most `max` rows, or `None` at the end.
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
        let [a, b, c, d] = self.angles;
        let chunk = match &mut self.src {
            Src::Csv(rdr) => {
                let cap = max.min(CHUNK_ROWS);
                let mut records = TextRows::with_capacity(cap, self.headers.len());
                let mut lines = Vec::with_capacity(cap);
                while lines.len() < max {
                    let Some(r) = rdr.next_record()? else {
                        break;
                    };
                    lines.push(r.line);
                    records.push(&r);
                }
                // Parsed in parallel; the first bad row (in file order) is the error.
                use rayon::prelude::*;
                let parsed: Vec<Result<Geometry>> = lines
                    .par_iter()
                    .enumerate()
                    .map(|(k, &line)| {
                        let f = |i| records.field(k, i);
                        row_geometry(&path, line, [f(a), f(b), f(c), f(d)])
                    })
                    .collect();
                let geometries = parsed.into_iter().collect::<Result<Vec<Geometry>>>()?;
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
                let mut geometries = Vec::with_capacity(n);
                let mut wavelengths = self.wavelength.map(|_| Vec::with_capacity(n));
                for (row, &line) in self.buf.chunks_exact(cols).zip(&lines) {
                    geometries.push(numeric_geometry(
                        &path,
                        line,
                        [row[a], row[b], row[c], row[d]],
                    )?);
                    if let (Some(w), Some(out)) = (self.wavelength, wavelengths.as_mut()) {
                        out.push(checked_wavelength(&path, line, row[w])?);
                    }
                }
                GeometryChunk {
                    lines,
                    geometries,
                    wavelengths,
                    columns: Passthrough::Numbers(std::mem::take(&mut self.buf)),
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

/// A geometry from four angles in degrees read from a `.npy` row (same checks and messages as
/// a CSV row's).
fn numeric_geometry(path: &Path, line: usize, deg: [f64; 4]) -> Result<Geometry> {
    crate::csv_io::geometry_of_degrees(path, line, deg)
}

fn checked_wavelength(path: &Path, line: usize, v: f64) -> Result<f64> {
    crate::csv_io::check_wavelength(path, line, v)
}

/// The 19 numbers `eval` appends for one pBRDF: brdf, dolp, aolp_deg, then F row-major.
pub fn result_values(f: &Mueller) -> [f64; 19] {
    // The reflected Stokes vector for unpolarized input, F·(1, 0, 0, 0): its DoLP and AoLP as
    // the core defines them.
    let s = f.first_column();
    let mut v = [0.0; 19];
    v[0] = f.m00();
    v[1] = s.dolp();
    v[2] = s.aolp().to_degrees();
    v[3..].copy_from_slice(&f.to_row_major());
    v
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

    /// The output's name.
    fn shown(&self) -> PathBuf {
        match &self.sink {
            Sink::Csv { out, .. } | Sink::NpySpool { out, .. } => out.path().to_path_buf(),
            Sink::Npy(w) => w.get_ref().path().to_path_buf(),
        }
    }

    /// Writes one chunk's rows with their pBRDFs.
    ///
    /// # Errors
    /// [`Error::Write`]; [`Error::Field`] naming the input's line and column when a `.npy`
    /// output is given a CSV column that is not a number.
    pub fn write_chunk(&mut self, chunk: &GeometryChunk, pbrdf: &[Mueller]) -> Result<()> {
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
        }
    }
}

/// One CSV row of the result table: row `k`'s input columns, then its 19 result values.
fn csv_row(line: &mut Vec<u8>, columns: &Passthrough, k: usize, cols: usize, f: &Mueller) {
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
    pbrdf: &[Mueller],
    headers: &[String],
    input: &Path,
) -> Result<()> {
    let cols = headers.len();
    row.clear();
    for (k, f) in pbrdf.iter().enumerate() {
        match &chunk.columns {
            Passthrough::Text(recs) => {
                for (field, name) in recs.row(k).zip(headers) {
                    let v =
                        parse_number(input, chunk.lines[k], name, field).map_err(|e| match e {
                            Error::Field {
                                path,
                                line,
                                field,
                                message,
                            } => Error::Field {
                                path,
                                line,
                                field,
                                message: format!("{message} (a .npy output holds numbers only)"),
                            },
                            other => other,
                        })?;
                    row.push(v);
                }
            }
            Passthrough::Numbers(v) => row.extend_from_slice(&v[k * cols..(k + 1) * cols]),
        }
        row.extend_from_slice(&result_values(f));
    }
    Ok(())
}
