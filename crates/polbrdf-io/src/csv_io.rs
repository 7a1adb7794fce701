//! Geometry CSV in, result CSV out (the `polbrdf eval` contract in the README).

use crate::error::{Error, Result};
use polbrdf::{Geometry, Stokes};
use std::collections::hash_map::{Entry, HashMap};
use std::io::{BufRead, Read};
use std::path::{Path, PathBuf};

/// The four angle columns every geometry file must have (degrees, any order).
pub const ANGLE_COLUMNS: [&str; 4] = ["theta_i_deg", "phi_i_deg", "theta_r_deg", "phi_r_deg"];

/// The columns `polbrdf eval` reads instead of [`ANGLE_COLUMNS`]: the direction vectors `w_i`
/// (toward the source) and `w_r` (toward the detector) in the surface frame, z along the
/// normal, of any length within `polbrdf::geometry::angles::DIRECTION_LENGTH` (docs/model.md
/// §9.11; the core's `DirectionBatch`).
pub const DIRECTION_COLUMNS: [&str; 6] = ["w_i_x", "w_i_y", "w_i_z", "w_r_x", "w_r_y", "w_r_z"];

/// The columns `polbrdf eval` appends: `brdf, dolp, aolp_deg, m00 … m33`.
pub fn result_columns() -> Vec<String> {
    let mut cols = vec!["brdf".to_string(), "dolp".into(), "aolp_deg".into()];
    cols.extend(polbrdf::Mueller::COLUMNS.map(String::from));
    cols
}

/// A parsed geometry file: the raw rows (copied through unchanged) and the validated
/// geometries.
#[derive(Debug, Clone)]
pub struct GeometryTable {
    /// Where it came from (`-` for standard input).
    pub path: PathBuf,
    /// Header names as written (surrounding whitespace trimmed).
    pub headers: Vec<String>,
    /// Every data row's fields, unchanged.
    pub rows: Vec<Vec<String>>,
    /// 1-based line number of each row.
    pub lines: Vec<usize>,
    /// One validated geometry per row.
    pub geometries: Vec<Geometry>,
    /// The `wavelength_um` column (µm, finite and > 0), when the file has one: the wavelength
    /// of each row for a spectral material (the column is also copied through).
    pub wavelengths: Option<Vec<f64>>,
}

/// The optional wavelength column of geometry and measurement files (µm).
pub const WAVELENGTH_COLUMN: &str = "wavelength_um";

/// The most bytes of a file read whole (`read_all`: material, scene, `lut` configuration,
/// refractive-index and whole `.npy` files): 16 MiB, far above any such file (the library's
/// largest index file is under 100 kB), so that a device or a huge file named by mistake
/// (`--material /dev/zero`) is an error naming it instead of a read until memory runs out.
pub const MAX_WHOLE_FILE_BYTES: u64 = 16 << 20;

/// The bytes of `path`, or of standard input for `-`, read whole (for the small files only:
/// material, scene and refractive-index files; every CSV reader streams, [`CsvReader`]), at
/// most [`MAX_WHOLE_FILE_BYTES`].
///
/// # Errors
/// [`Error::Read`]; [`Error::File`] for a file longer than the bound.
pub(crate) fn read_all(path: &Path) -> Result<Vec<u8>> {
    let read_err = |source| Error::Read {
        path: path.to_path_buf(),
        source,
    };
    let src: Box<dyn Read> = if path.as_os_str() == "-" {
        Box::new(std::io::stdin())
    } else {
        Box::new(std::fs::File::open(path).map_err(read_err)?)
    };
    let mut buf = Vec::new();
    // One byte past the bound tells a file at the bound from a longer one.
    src.take(MAX_WHOLE_FILE_BYTES + 1)
        .read_to_end(&mut buf)
        .map_err(read_err)?;
    if buf.len() as u64 > MAX_WHOLE_FILE_BYTES {
        return Err(Error::File {
            path: path.to_path_buf(),
            message: format!(
                "longer than {} MiB: this file is read whole, and no file of its kind is that \
                 long (is it the file meant?)",
                MAX_WHOLE_FILE_BYTES >> 20
            ),
        });
    }
    Ok(buf)
}

/// The 1-based line of byte `pos` of `text` (for TOML spans).
pub(crate) fn line_of(text: &str, pos: usize) -> usize {
    text.as_bytes()[..pos.min(text.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

/// The text of `path` ([`read_all`]); bytes that are not UTF-8 are an error naming the line.
pub(crate) fn read_text(path: &Path) -> Result<String> {
    String::from_utf8(read_all(path)?).map_err(|e| {
        let pos = e.utf8_error().valid_up_to();
        Error::Syntax {
            path: path.to_path_buf(),
            line: line_of(&String::from_utf8_lossy(&e.as_bytes()[..pos]), pos),
            message: "file is not valid UTF-8 text".into(),
        }
    })
}

/// The longest line a CSV reader accepts (bytes, line end excluded): a header of 10⁵ columns
/// fits; a longer line is an error naming it, so that no single line can exhaust memory.
pub const MAX_LINE_BYTES: usize = 1 << 20;

/// The most characters of one name (CSV column, TOML key) quoted in a message; longer names are
/// cut with `…` so that every message stays under the project's 2 kB bound.
pub const MAX_NAME_IN_MESSAGE: usize = 80;

/// The most characters of a list of names (the header, the keys of a table) in a message.
pub const MAX_LIST_IN_MESSAGE: usize = 1000;

/// `name` for a message: at most [`MAX_NAME_IN_MESSAGE`] characters.
pub fn short_name(name: &str) -> String {
    cut(name, MAX_NAME_IN_MESSAGE)
}

/// `names` joined by `, ` for a message: at most [`MAX_LIST_IN_MESSAGE`] characters, each name
/// shortened, and the number of names left out said.
pub fn short_list<S: AsRef<str>>(names: &[S]) -> String {
    let mut out = String::new();
    for (i, n) in names.iter().enumerate() {
        let n = short_name(n.as_ref());
        if out.len() + n.len() > MAX_LIST_IN_MESSAGE {
            out.push_str(&format!(" … and {} more", names.len() - i));
            break;
        }
        if i > 0 {
            out.push_str(", ");
        }
        out.push_str(&n);
    }
    out
}

/// `text` with every lone `\r` (an old Mac line end) made a `\n`, so that the TOML readers
/// count lines as the CSV readers do (`\n`, `\r\n` or `\r`); `\r\n` is kept.
pub(crate) fn lone_cr_to_lf(text: &str) -> std::borrow::Cow<'_, str> {
    let b = text.as_bytes();
    let lone = |i: usize| b[i] == b'\r' && b.get(i + 1) != Some(&b'\n');
    if !(0..b.len()).any(lone) {
        return std::borrow::Cow::Borrowed(text);
    }
    let out: Vec<u8> = (0..b.len())
        .map(|i| if lone(i) { b'\n' } else { b[i] })
        .collect();
    // Only ASCII bytes were replaced by ASCII bytes.
    std::borrow::Cow::Owned(String::from_utf8(out).expect("still UTF-8"))
}

/// A message from another crate (the TOML parser's, which may quote a key), cut to 1000
/// characters.
pub(crate) fn short_message(m: &str) -> String {
    cut(m, MAX_LIST_IN_MESSAGE)
}

fn cut(s: &str, max: usize) -> String {
    if s.chars().count() > max {
        s.chars().take(max).collect::<String>() + "…"
    } else {
        s.to_string()
    }
}

/// A streaming CSV reader for the project's numeric tables: one record per physical line.
///
/// Lines end at `\n`, `\r\n` or a lone `\r` (old Mac files), a UTF-8 BOM is skipped, blank lines
/// are skipped (and counted), fields are separated by `,` and may be quoted (`"a,b"`, `""` for a
/// quote). A quoted field never spans lines: none of our files has a newline inside a field, so
/// a quote still open at the end of a line is an error naming that line (the `csv` crate would
/// read the rest of the file into that field and silently drop every later row). Memory is
/// bounded by one line ([`MAX_LINE_BYTES`]), whatever the file's length.
pub struct CsvReader<R> {
    src: R,
    path: PathBuf,
    headers: Vec<String>,
    /// Physical line number of the last line read.
    line: usize,
    /// The raw bytes of the current line.
    raw: Vec<u8>,
    /// The unquoted text of the current record's fields, and each field's range in it.
    text: String,
    fields: Vec<std::ops::Range<usize>>,
    /// A lone `\r` ended the last line: a `\n` right after it belongs to it.
    after_cr: bool,
}

impl<R> std::fmt::Debug for CsvReader<R> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CsvReader")
            .field("path", &self.path)
            .field("line", &self.line)
            .finish_non_exhaustive()
    }
}

/// One record of a [`CsvReader`].
#[derive(Debug, Clone, Copy)]
pub struct Record<'a> {
    /// 1-based physical line.
    pub line: usize,
    text: &'a str,
    fields: &'a [std::ops::Range<usize>],
}

impl<'a> Record<'a> {
    /// Field `k` (unquoted, untrimmed).
    pub fn get(&self, k: usize) -> &'a str {
        &self.text[self.fields[k].clone()]
    }

    /// Number of fields.
    pub fn len(&self) -> usize {
        self.fields.len()
    }

    /// True for a record without fields (never returned by the reader).
    pub fn is_empty(&self) -> bool {
        self.fields.is_empty()
    }

    /// Every field, in order.
    pub fn iter(&self) -> impl Iterator<Item = &'a str> + '_ {
        self.fields.iter().map(|r| &self.text[r.clone()])
    }
}

impl CsvReader<Box<dyn BufRead>> {
    /// Opens `path` (`-` = standard input, read as a stream) and reads its header.
    ///
    /// # Errors
    /// [`Error::Read`] when it cannot be opened; else as [`CsvReader::new`].
    pub fn open(path: &Path) -> Result<Self> {
        let src: Box<dyn BufRead> = if path.as_os_str() == "-" {
            Box::new(std::io::stdin().lock())
        } else {
            let file = std::fs::File::open(path).map_err(|source| Error::Read {
                path: path.to_path_buf(),
                source,
            })?;
            Box::new(std::io::BufReader::with_capacity(1 << 16, file))
        };
        Self::new(src, path)
    }
}

impl<R: BufRead> CsvReader<R> {
    /// Reads the header line from `src`; `path` is used in messages only.
    ///
    /// # Errors
    /// [`Error::File`] for an empty file; [`Error::Syntax`] for bad UTF-8, an unclosed quote,
    /// a line over [`MAX_LINE_BYTES`] or a column named twice.
    pub fn new(src: R, path: &Path) -> Result<Self> {
        let mut r = Self {
            src,
            path: path.to_path_buf(),
            headers: Vec::new(),
            line: 0,
            raw: Vec::new(),
            text: String::new(),
            fields: Vec::new(),
            after_cr: false,
        };
        // The header is the first line that is not blank.
        while r.next_line()? && r.fields.is_empty() {}
        if !r.fields.is_empty() {
            r.headers = r
                .fields
                .iter()
                .map(|f| r.text[f.clone()].trim().to_string())
                .collect();
        }
        if r.headers.is_empty() || r.headers.iter().all(String::is_empty) {
            return Err(r.file_error("empty file: expected a header line naming the columns"));
        }
        let mut seen = std::collections::HashSet::with_capacity(r.headers.len());
        for h in &r.headers {
            if !seen.insert(h.as_str()) {
                return Err(Error::Syntax {
                    path: r.path.clone(),
                    line: r.line,
                    message: format!("column `{}` appears twice in the header", short_name(h)),
                });
            }
        }
        Ok(r)
    }

    /// The header's names (surrounding whitespace trimmed).
    pub fn headers(&self) -> &[String] {
        &self.headers
    }

    /// The file name used in messages.
    pub fn path(&self) -> &Path {
        &self.path
    }

    fn file_error(&self, message: &str) -> Error {
        Error::File {
            path: self.path.clone(),
            message: message.to_string(),
        }
    }

    /// The column index of each of `required`.
    ///
    /// # Errors
    /// [`Error::File`] naming the missing columns (and the header, shortened).
    pub fn require(&self, required: &[&str]) -> Result<Vec<usize>> {
        check_header(&self.headers, &self.path, required)
    }

    /// The next record, or `None` at the end of the file.
    ///
    /// # Errors
    /// [`Error::Read`]; [`Error::Syntax`] naming the line for bad UTF-8, an unclosed quote, a
    /// line over [`MAX_LINE_BYTES`] or a field count different from the header's.
    pub fn next_record(&mut self) -> Result<Option<Record<'_>>> {
        loop {
            if !self.next_line()? {
                return Ok(None);
            }
            if self.fields.is_empty() {
                continue; // a blank line
            }
            if self.fields.len() != self.headers.len() {
                return Err(Error::Syntax {
                    path: self.path.clone(),
                    line: self.line,
                    message: format!(
                        "row has {} fields, the header has {}",
                        self.fields.len(),
                        self.headers.len()
                    ),
                });
            }
            return Ok(Some(Record {
                line: self.line,
                text: &self.text,
                fields: &self.fields,
            }));
        }
    }

    fn syntax(&self, message: String) -> Error {
        Error::Syntax {
            path: self.path.clone(),
            line: self.line,
            message,
        }
    }

    /// Reads one physical line into `raw` and splits it into `fields` (none for a blank line);
    /// false at the end of the file.
    fn next_line(&mut self) -> Result<bool> {
        self.raw.clear();
        let mut ended = false;
        let mut any = false;
        while !ended {
            let buf = self.src.fill_buf().map_err(|source| Error::Read {
                path: self.path.clone(),
                source,
            })?;
            if buf.is_empty() {
                break;
            }
            let mut start = 0;
            if self.after_cr {
                self.after_cr = false;
                if buf[0] == b'\n' {
                    start = 1;
                }
            }
            let (take, used) = match buf[start..].iter().position(|&b| b == b'\n' || b == b'\r') {
                Some(i) => {
                    ended = true;
                    if buf[start + i] == b'\r' {
                        self.after_cr = true;
                    }
                    (start + i, start + i + 1)
                }
                None => (buf.len(), buf.len()),
            };
            any |= take > start || ended;
            if self.raw.len() + (take - start) > MAX_LINE_BYTES {
                self.line += 1;
                return Err(self.syntax(format!(
                    "line longer than {MAX_LINE_BYTES} bytes (is this a CSV file?)"
                )));
            }
            self.raw.extend_from_slice(&buf[start..take]);
            self.src.consume(used);
        }
        if !any {
            return Ok(false);
        }
        self.line += 1;
        let mut bytes = &self.raw[..];
        if self.line == 1 {
            bytes = bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(bytes);
        }
        let line = std::str::from_utf8(bytes)
            .map_err(|_| self.syntax("not valid UTF-8 text (is this a CSV file?)".into()))?;
        self.text.clear();
        self.fields.clear();
        if line.is_empty() {
            return Ok(true);
        }
        // Fields as the csv crate reads them: a field that starts with `"` is quoted up to the
        // next lone `"` (`""` is a quote), anything after that up to the comma is kept as is.
        let mut chars = line.chars().peekable();
        loop {
            let begin = self.text.len();
            if chars.peek() == Some(&'"') {
                chars.next();
                let mut closed = false;
                while let Some(c) = chars.next() {
                    if c == '"' {
                        if chars.peek() == Some(&'"') {
                            chars.next();
                            self.text.push('"');
                        } else {
                            closed = true;
                            break;
                        }
                    } else {
                        self.text.push(c);
                    }
                }
                if !closed {
                    return Err(self.syntax(
                        "a quote opened on this line is not closed on it (a field cannot span \
                         lines)"
                            .into(),
                    ));
                }
            }
            let mut more = false;
            for c in chars.by_ref() {
                if c == ',' {
                    more = true;
                    break;
                }
                self.text.push(c);
            }
            self.fields.push(begin..self.text.len());
            if !more {
                break;
            }
        }
        Ok(true)
    }
}

/// Reads every record of `reader`, calling `row` on each: the streaming loop of the numeric
/// readers.
fn for_each_record<R: BufRead>(
    reader: &mut CsvReader<R>,
    mut row: impl FnMut(&Record<'_>) -> Result<()>,
) -> Result<()> {
    while let Some(r) = reader.next_record()? {
        row(&r)?;
    }
    Ok(())
}

/// Parses a number in a CSV field (surrounding whitespace allowed).
pub(crate) fn parse_number(path: &Path, line: usize, column: &str, field: &str) -> Result<f64> {
    field.trim().parse::<f64>().map_err(|_| Error::Field {
        path: path.to_path_buf(),
        line,
        field: column.to_string(),
        message: format!("expected a number, got {:?}", cut(field, 40)),
    })
}

/// A number in a message: as it would be written, in exponent form when very large or small
/// (as the core's messages show values).
pub(crate) fn show(v: f64) -> String {
    if v == 0.0 || !v.is_finite() || (1e-5..1e16).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// Reads a geometry CSV (`-` = standard input): a header holding `theta_i_deg, phi_i_deg,
/// theta_r_deg, phi_r_deg` in any order, other columns kept as they are.
///
/// # Errors
/// [`Error::Read`], [`Error::Syntax`] (bad CSV or UTF-8, with the line), [`Error::File`] (empty
/// file, missing columns), [`Error::Field`] (a non-number or an invalid angle, with line and
/// column).
pub fn read_geometry_csv(path: &Path) -> Result<GeometryTable> {
    geometry_chunk(&mut CsvReader::open(path)?, usize::MAX)
}

/// Parses the bytes of a geometry CSV; `path` is used in messages only.
///
/// # Errors
/// As [`read_geometry_csv`], except [`Error::Read`].
pub fn parse_geometry_csv(bytes: &[u8], path: &Path) -> Result<GeometryTable> {
    geometry_chunk(&mut CsvReader::new(bytes, path)?, usize::MAX)
}

/// Checks a table's header (CSV or `.npy`): not empty, no column twice, every `required` column
/// present; returns the index of each required column.
pub(crate) fn check_header(
    headers: &[String],
    path: &Path,
    required: &[&str],
) -> Result<Vec<usize>> {
    if headers.is_empty() || headers.iter().all(String::is_empty) {
        return Err(Error::File {
            path: path.to_path_buf(),
            message: format!(
                "empty file: expected a header line naming the columns {}",
                required.join(", ")
            ),
        });
    }
    let mut seen = std::collections::HashSet::with_capacity(headers.len());
    if let Some(h) = headers.iter().find(|h| !seen.insert(h.as_str())) {
        return Err(Error::Syntax {
            path: path.to_path_buf(),
            line: 1,
            message: format!("column `{}` appears twice in the header", short_name(h)),
        });
    }
    let position = |r: &str| headers.iter().position(|h| h == r);
    let missing: Vec<&str> = required
        .iter()
        .copied()
        .filter(|r| position(r).is_none())
        .collect();
    if missing.len() == required.len() {
        // Not a table of this kind (a scene may name any file, `/etc/passwd`): its first line
        // is not shown.
        return Err(Error::File {
            path: path.to_path_buf(),
            message: format!(
                "missing column(s) {}: the first line names none of them, so this is not a \
                 table of that kind (its content is not shown)",
                missing.join(", "),
            ),
        });
    }
    if !missing.is_empty() {
        return Err(Error::File {
            path: path.to_path_buf(),
            message: format!(
                "missing column(s) {} (the header has: {})",
                missing.join(", "),
                short_list(headers)
            ),
        });
    }
    Ok(required
        .iter()
        .map(|r| position(r).expect("checked above"))
        .collect())
}

/// The geometry of a record, from the angle columns at `idx` (in [`ANGLE_COLUMNS`] order).
pub(crate) fn record_geometry(path: &Path, r: &Record<'_>, idx: &[usize]) -> Result<Geometry> {
    row_geometry(path, r.line, [0, 1, 2, 3].map(|k| r.get(idx[k])))
}

/// The wavelength of a record (µm, finite and > 0), from column `c`.
pub(crate) fn record_wavelength(path: &Path, r: &Record<'_>, c: usize) -> Result<f64> {
    row_wavelength(path, r.line, r.get(c))
}

/// The geometry of a row from its four angle fields (in [`ANGLE_COLUMNS`] order, degrees).
pub(crate) fn row_geometry(path: &Path, line: usize, fields: [&str; 4]) -> Result<Geometry> {
    let mut deg = [0.0; 4];
    for (k, d) in deg.iter_mut().enumerate() {
        *d = parse_number(path, line, ANGLE_COLUMNS[k], fields[k])?;
    }
    geometry_of_degrees(path, line, deg)
}

/// The geometry of four angles in degrees ([`ANGLE_COLUMNS`] order) at a row's line; an
/// invalid angle is an error naming its column.
pub(crate) fn geometry_of_degrees(path: &Path, line: usize, deg: [f64; 4]) -> Result<Geometry> {
    Geometry::from_degrees(deg[0], deg[1], deg[2], deg[3]).map_err(|e| {
        let field = match &e {
            polbrdf::Error::InvalidAngle { name, .. } => name.to_string(),
            _ => "angles".to_string(),
        };
        Error::Field {
            path: path.to_path_buf(),
            line,
            field,
            message: e.to_string(),
        }
    })
}

/// The direction vectors `(w_i, w_r)` of a row's six direction fields ([`DIRECTION_COLUMNS`]
/// order): numbers, each vector as [`directions_of`] checks it.
pub(crate) fn row_directions(
    path: &Path,
    line: usize,
    fields: [&str; 6],
) -> Result<([f64; 3], [f64; 3])> {
    let mut v = [0.0; 6];
    for (k, x) in v.iter_mut().enumerate() {
        *x = parse_number(path, line, DIRECTION_COLUMNS[k], fields[k])?;
    }
    directions_of(path, line, v)
}

/// The direction vectors of six numbers at a row's line ([`DIRECTION_COLUMNS`] order): every
/// component finite (an error naming its column) and each vector of a length the core's
/// `DirectionBatch` accepts (an error naming the vector's three columns, with the core's
/// message).
pub(crate) fn directions_of(path: &Path, line: usize, v: [f64; 6]) -> Result<([f64; 3], [f64; 3])> {
    if let Some(k) = v.iter().position(|x| !x.is_finite()) {
        return Err(Error::Field {
            path: path.to_path_buf(),
            line,
            field: DIRECTION_COLUMNS[k].into(),
            message: format!("{}: a direction component must be finite", show(v[k])),
        });
    }
    let (w_i, w_r) = ([v[0], v[1], v[2]], [v[3], v[4], v[5]]);
    match polbrdf::DirectionBatch::new(std::slice::from_ref(&w_i), std::slice::from_ref(&w_r)) {
        Ok(_) => Ok((w_i, w_r)),
        Err(e) => {
            // The line names the row: the core's message without its index in the batch of one.
            let (columns, e) = match e {
                polbrdf::Error::InvalidDirection { name, value, .. } => (
                    if name == "w_r" {
                        &DIRECTION_COLUMNS[3..]
                    } else {
                        &DIRECTION_COLUMNS[..3]
                    },
                    polbrdf::Error::InvalidDirection {
                        name,
                        value,
                        index: None,
                    },
                ),
                other => (&DIRECTION_COLUMNS[..], other),
            };
            Err(Error::Field {
                path: path.to_path_buf(),
                line,
                field: columns.join(", "),
                message: e.to_string(),
            })
        }
    }
}

/// A row's `wavelength_um` field: a number, finite and > 0 (µm).
pub(crate) fn row_wavelength(path: &Path, line: usize, field: &str) -> Result<f64> {
    check_wavelength(
        path,
        line,
        parse_number(path, line, WAVELENGTH_COLUMN, field)?,
    )
}

/// A wavelength (µm) at a row's line: finite and > 0.
pub(crate) fn check_wavelength(path: &Path, line: usize, v: f64) -> Result<f64> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(Error::Field {
            path: path.to_path_buf(),
            line,
            field: WAVELENGTH_COLUMN.into(),
            message: format!("{v}: a wavelength must be finite and > 0 (µm)"),
        })
    }
}

/// The next at most `max_rows` rows of a geometry CSV as a table (no rows at the end of the
/// file): the chunked form of [`read_geometry_csv`], whose memory is bounded by the chunk.
/// Open the reader with [`CsvReader::open`] or [`CsvReader::new`].
///
/// # Errors
/// As [`read_geometry_csv`].
pub fn geometry_chunk<R: BufRead>(
    reader: &mut CsvReader<R>,
    max_rows: usize,
) -> Result<GeometryTable> {
    let idx = reader.require(&ANGLE_COLUMNS)?;
    let wl = reader.headers.iter().position(|h| h == WAVELENGTH_COLUMN);
    let path = reader.path.clone();
    let headers = reader.headers.clone();
    let (mut rows, mut lines, mut geometries) = (Vec::new(), Vec::new(), Vec::new());
    let mut wavelengths = wl.map(|_| Vec::new());
    while rows.len() < max_rows {
        let Some(r) = reader.next_record()? else {
            break;
        };
        geometries.push(record_geometry(&path, &r, &idx)?);
        if let (Some(c), Some(w)) = (wl, wavelengths.as_mut()) {
            w.push(record_wavelength(&path, &r, c)?);
        }
        lines.push(r.line);
        rows.push(r.iter().map(str::to_string).collect());
    }
    Ok(GeometryTable {
        path,
        headers,
        rows,
        lines,
        geometries,
        wavelengths,
    })
}

/// The columns of a band file: the wavelength (µm) and the relative spectral response.
pub const BAND_COLUMNS: [&str; 2] = ["wavelength_um", "response"];

/// Reads a band file (CSV with columns `wavelength_um, response`: a relative spectral response,
/// linear between the rows and zero outside, wavelengths strictly increasing).
///
/// # Errors
/// [`Error::Field`] naming the file, the line and the column for a malformed or invalid value;
/// [`Error::File`] for a missing column, fewer than two rows, or a response zero everywhere;
/// [`Error::Field`] at the row after the [`polbrdf::analysis::spectral::MAX_BAND_ROWS`]th
/// (the file is read no further).
pub fn read_band_csv(path: &Path) -> Result<polbrdf::Band> {
    band_from(CsvReader::open(path)?)
}

/// Parses band CSV bytes ([`read_band_csv`]); `path` is used in messages only.
///
/// # Errors
/// As [`read_band_csv`].
pub fn parse_band_csv(bytes: &[u8], path: &Path) -> Result<polbrdf::Band> {
    band_from(CsvReader::new(bytes, path)?)
}

fn band_from<R: BufRead>(mut reader: CsvReader<R>) -> Result<polbrdf::Band> {
    let index = reader.require(&BAND_COLUMNS)?;
    let path = reader.path.clone();
    let path = path.as_path();
    let (mut wl, mut response, mut lines) = (Vec::new(), Vec::new(), Vec::new());
    // Read up to one row past the core's bound (which names that row): no further.
    while wl.len() <= polbrdf::analysis::spectral::MAX_BAND_ROWS {
        let Some(r) = reader.next_record()? else {
            break;
        };
        wl.push(parse_number(
            path,
            r.line,
            BAND_COLUMNS[0],
            r.get(index[0]),
        )?);
        response.push(parse_number(
            path,
            r.line,
            BAND_COLUMNS[1],
            r.get(index[1]),
        )?);
        lines.push(r.line);
    }
    let name = path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    polbrdf::Band::new(&name, wl, response).map_err(|e| row_error(path, &lines, e))
}

/// A core error about the row `index` of a table (`InvalidParameterAt`) at that row's line;
/// any other as an error of the whole file.
pub(crate) fn row_error(path: &Path, lines: &[usize], e: polbrdf::Error) -> Error {
    match e {
        polbrdf::Error::InvalidParameterAt { name, index, .. } => Error::Field {
            path: path.to_path_buf(),
            line: lines[index],
            field: name.to_string(),
            message: e.to_string(),
        },
        other => Error::File {
            path: path.to_path_buf(),
            message: other.to_string(),
        },
    }
}

/// The columns of a sky profile file: the zenith angle of a sky point (degrees) and the sky's
/// spectral radiance there (W·m⁻²·sr⁻¹·µm⁻¹).
pub const SKY_PROFILE_COLUMNS: [&str; 2] = ["zenith_deg", "radiance"];

/// Reads a sky profile file (CSV with columns `zenith_deg, radiance` in any order: an
/// unpolarized sky's radiance by zenith angle, linear between the rows, zenith angles strictly
/// increasing from 0° to 90°; [`polbrdf::analysis::sky::ZenithProfile`]).
///
/// # Errors
/// [`Error::Field`] naming the file, the line and the column for a malformed or invalid value
/// (a zenith angle outside [0°, 90°] or not above the previous one, a radiance that is not
/// finite and ≥ 0); [`Error::File`] for a missing column, fewer than two rows, or a table that
/// does not start at 0° and end at 90°.
pub fn read_sky_profile_csv(path: &Path) -> Result<polbrdf::analysis::sky::ZenithProfile> {
    sky_profile_from(CsvReader::open(path)?)
}

/// Parses sky profile CSV bytes ([`read_sky_profile_csv`]); `path` is used in messages only.
///
/// # Errors
/// As [`read_sky_profile_csv`].
pub fn parse_sky_profile_csv(
    bytes: &[u8],
    path: &Path,
) -> Result<polbrdf::analysis::sky::ZenithProfile> {
    sky_profile_from(CsvReader::new(bytes, path)?)
}

fn sky_profile_from<R: BufRead>(
    mut reader: CsvReader<R>,
) -> Result<polbrdf::analysis::sky::ZenithProfile> {
    let index = reader.require(&SKY_PROFILE_COLUMNS)?;
    let path = reader.path.clone();
    let path = path.as_path();
    let (mut zenith, mut radiance, mut lines) = (Vec::new(), Vec::new(), Vec::new());
    for_each_record(&mut reader, |r| {
        zenith.push(parse_number(
            path,
            r.line,
            SKY_PROFILE_COLUMNS[0],
            r.get(index[0]),
        )?);
        radiance.push(parse_number(
            path,
            r.line,
            SKY_PROFILE_COLUMNS[1],
            r.get(index[1]),
        )?);
        lines.push(r.line);
        Ok(())
    })?;
    polbrdf::analysis::sky::ZenithProfile::new(zenith, radiance)
        .map_err(|e| row_error(path, &lines, e))
}

/// The columns of a sky table file: the direction of a sky point (zenith angle and azimuth,
/// degrees) and the Stokes radiance arriving from it, in the arriving beam's psps basis.
pub const SKY_TABLE_COLUMNS: [&str; 6] = ["theta_deg", "phi_deg", "s0", "s1", "s2", "s3"];

/// Reads a sky table file (CSV with columns `theta_deg, phi_deg, s0, s1, s2, s3` in any order,
/// other columns ignored; [`polbrdf::analysis::sky::TableSky`]): the Stokes radiance of a sky
/// on a full grid of zenith angles × azimuths. The rows may come in any order; the grid is
/// made of the distinct zenith angles (which must include 0° and 90°) and the distinct
/// azimuths (in `[0°, 360°)`: the table is periodic, 360° is 0°), and every node of it must be
/// given exactly once.
///
/// # Errors
/// [`Error::Field`] naming the file, the line and the column for a malformed value, an angle
/// out of range, a non-finite Stokes parameter, `s0 < 0` or a degree of polarization above 1,
/// and for a node given twice (naming both lines); [`Error::File`] for a missing column, a
/// file without rows, a grid with a hole (naming the missing node and the grid) or zenith
/// angles that do not span 0° to 90°.
pub fn read_sky_table_csv(path: &Path) -> Result<polbrdf::analysis::sky::TableSky> {
    sky_table_from(CsvReader::open(path)?)
}

/// Parses sky table CSV bytes ([`read_sky_table_csv`]); `path` is used in messages only.
///
/// # Errors
/// As [`read_sky_table_csv`].
pub fn parse_sky_table_csv(bytes: &[u8], path: &Path) -> Result<polbrdf::analysis::sky::TableSky> {
    sky_table_from(CsvReader::new(bytes, path)?)
}

fn sky_table_from<R: BufRead>(
    mut reader: CsvReader<R>,
) -> Result<polbrdf::analysis::sky::TableSky> {
    let index = reader.require(&SKY_TABLE_COLUMNS)?;
    let path = reader.path.clone();
    let path = path.as_path();
    let field = |line: usize, column: &str, message: String| Error::Field {
        path: path.to_path_buf(),
        line,
        field: column.to_string(),
        message,
    };
    // Every row's values, its angles checked (−0 read as 0).
    let (mut values, mut lines) = (Vec::new(), Vec::new());
    for_each_record(&mut reader, |r| {
        let line = r.line;
        let mut v = [0.0; 6];
        for (k, x) in v.iter_mut().enumerate() {
            *x = parse_number(path, line, SKY_TABLE_COLUMNS[k], r.get(index[k]))? + 0.0;
        }
        if !(v[0].is_finite() && (0.0..=90.0).contains(&v[0])) {
            return Err(field(
                line,
                SKY_TABLE_COLUMNS[0],
                format!("{}: a zenith angle must lie in [0°, 90°]", show(v[0])),
            ));
        }
        if !(v[1].is_finite() && (0.0..360.0).contains(&v[1])) {
            return Err(field(
                line,
                SKY_TABLE_COLUMNS[1],
                format!(
                    "{}: an azimuth must lie in [0°, 360°) (the table is periodic in azimuth: \
                     give 360° as 0°, once)",
                    show(v[1])
                ),
            ));
        }
        values.push(v);
        lines.push(line);
        Ok(())
    })?;
    if values.is_empty() {
        return Err(Error::File {
            path: path.to_path_buf(),
            message: "no rows (the file has a header but no sky nodes)".into(),
        });
    }
    let distinct = |k: usize| {
        let mut a: Vec<f64> = values.iter().map(|v| v[k]).collect();
        a.sort_by(f64::total_cmp);
        a.dedup();
        a
    };
    let (theta, phi) = (distinct(0), distinct(1));
    let (nt, np) = (theta.len(), phi.len());
    let position = |a: &[f64], x: f64| a.binary_search_by(|v| v.total_cmp(&x)).expect("in it");
    // The row of each node given, by (zenith index, azimuth index): memory by the rows, not by
    // the grid they span (10⁵ rows of distinct angles span 10¹⁰ nodes: issue 35).
    let mut node_row: HashMap<(usize, usize), usize> = HashMap::with_capacity(values.len());
    for (r, v) in values.iter().enumerate() {
        match node_row.entry((position(&theta, v[0]), position(&phi, v[1]))) {
            Entry::Occupied(first) => {
                return Err(field(
                    lines[r],
                    "theta_deg,phi_deg",
                    format!(
                        "the node (theta_deg = {}, phi_deg = {}) is given twice: at lines {} \
                         and {}",
                        show(v[0]),
                        show(v[1]),
                        lines[*first.get()],
                        lines[r]
                    ),
                ))
            }
            Entry::Vacant(e) => {
                e.insert(r);
            }
        }
    }
    // Every node given once: there are as many nodes as rows.
    let grid = nt as u128 * np as u128;
    if (node_row.len() as u128) < grid {
        return Err(sky_table_hole(path, &theta, &phi, &node_row, values.len()));
    }
    let mut order = vec![0; nt * np];
    for ((t, p), r) in node_row {
        order[t * np + p] = r;
    }
    let stokes = order
        .iter()
        .map(|&r| {
            let v = values[r];
            Stokes([v[2], v[3], v[4], v[5]])
        })
        .collect();
    let nodes = (theta.clone(), phi.clone());
    polbrdf::analysis::sky::TableSky::new(theta, phi, stokes).map_err(|e| match e {
        // The Stokes parameters are indexed by node (the angles cannot be wrong here): the
        // message names the node instead of its index.
        polbrdf::Error::InvalidParameterAt {
            name,
            value,
            index,
            reason,
        } if name.starts_with('s') && index < order.len() => field(
            lines[order[index]],
            name,
            format!(
                "invalid parameter `{name}` = {} (at the node theta_deg = {}, phi_deg = {}): \
                 {reason}",
                show(value),
                show(nodes.0[index / np]),
                show(nodes.1[index % np])
            ),
        ),
        other => Error::File {
            path: path.to_path_buf(),
            message: other.to_string(),
        },
    })
}

/// The error of a sky table whose rows leave a node of their grid (zenith angles `theta` ×
/// azimuths `phi`) without a row: it names the first missing node (θ-major), the grid and how
/// many nodes are missing. Time and memory by the rows given (`node_row`), never by the grid.
fn sky_table_hole(
    path: &Path,
    theta: &[f64],
    phi: &[f64],
    node_row: &HashMap<(usize, usize), usize>,
    rows: usize,
) -> Error {
    let np = phi.len() as u128;
    let mut given: Vec<u128> = node_row
        .keys()
        .map(|&(t, p)| t as u128 * np + p as u128)
        .collect();
    given.sort_unstable();
    // The first index not given: the first k with given[k] ≠ k (the indices are distinct).
    let hole = given
        .iter()
        .enumerate()
        .find(|&(k, &g)| g != k as u128)
        .map_or(given.len() as u128, |(k, _)| k as u128);
    let nodes = theta.len() as u128 * np;
    let missing = nodes - given.len() as u128;
    let list = |a: &[f64]| {
        let shown: Vec<String> = if a.len() <= 12 {
            a.iter().map(|x| show(*x)).collect()
        } else {
            a[..5]
                .iter()
                .map(|x| show(*x))
                .chain(["…".to_string()])
                .chain(a[a.len() - 5..].iter().map(|x| show(*x)))
                .collect()
        };
        shown.join(", ")
    };
    Error::File {
        path: path.to_path_buf(),
        message: format!(
            "the sky table has a hole: no row for the node (theta_deg = {}, phi_deg = {}); the \
             grid of its zenith angles [{}] × azimuths [{}] has {} nodes, each needed once, and \
             {} of them {} missing ({} rows given)",
            show(theta[(hole / np) as usize]),
            show(phi[(hole % np) as usize]),
            list(theta),
            list(phi),
            nodes,
            missing,
            if missing == 1 { "is" } else { "are" },
            rows
        ),
    }
}

/// The columns of a view-direction file: the view zenith and azimuth angles in degrees.
pub const VIEW_COLUMNS: [&str; 2] = ["theta_r_deg", "phi_r_deg"];

/// Reads a view-direction file (CSV with columns `theta_r_deg, phi_r_deg` in any order; other
/// columns are ignored, so a geometry or result table can be reused) and returns the
/// `(θ_r, φ_r)` pairs in degrees, in file order.
///
/// # Errors
/// [`Error::Field`] naming the file, the line and the column for a value that is not a number,
/// a view zenith angle outside [0°, 90°) or a non-finite azimuth; [`Error::File`] for a missing
/// column or a file without rows.
pub fn read_views_csv(path: &Path) -> Result<Vec<(f64, f64)>> {
    views_from(CsvReader::open(path)?)
}

/// Parses view-direction CSV bytes ([`read_views_csv`]); `path` is used in messages only.
///
/// # Errors
/// As [`read_views_csv`].
pub fn parse_views_csv(bytes: &[u8], path: &Path) -> Result<Vec<(f64, f64)>> {
    views_from(CsvReader::new(bytes, path)?)
}

fn views_from<R: BufRead>(mut reader: CsvReader<R>) -> Result<Vec<(f64, f64)>> {
    let index = reader.require(&VIEW_COLUMNS)?;
    let path = reader.path.clone();
    let path = path.as_path();
    let field = |line: usize, column: &str, message: String| Error::Field {
        path: path.to_path_buf(),
        line,
        field: column.to_string(),
        message,
    };
    let mut views = Vec::new();
    for_each_record(&mut reader, |r| {
        let line = r.line;
        let theta = parse_number(path, line, VIEW_COLUMNS[0], r.get(index[0]))?;
        let phi = parse_number(path, line, VIEW_COLUMNS[1], r.get(index[1]))?;
        if !(0.0..90.0).contains(&theta) {
            return Err(field(
                line,
                VIEW_COLUMNS[0],
                format!("{theta}: the view zenith angle must lie in [0, 90) degrees"),
            ));
        }
        if !(phi.is_finite() && phi.abs() <= polbrdf::MAX_AZIMUTH_DEG) {
            return Err(field(
                line,
                VIEW_COLUMNS[1],
                format!(
                    "{}: must be finite and within ±{}° (beyond it too few digits of the angle \
                     remain)",
                    show(phi),
                    show(polbrdf::MAX_AZIMUTH_DEG)
                ),
            ));
        }
        views.push((theta, phi));
        Ok(())
    })?;
    if views.is_empty() {
        return Err(Error::File {
            path: path.to_path_buf(),
            message: "no view directions (the file has a header but no rows)".into(),
        });
    }
    Ok(views)
}

/// Shortest round-trip text of a finite `f64` (`-0.0` printed as `0.0`).
pub fn fmt_f64(v: f64) -> String {
    let mut b = Vec::with_capacity(24);
    fmt_f64_into(v, &mut b);
    String::from_utf8(b).expect("ASCII")
}

/// Appends [`fmt_f64`]'s text of `v` to `out`, without allocating: shortest round-trip digits
/// by `zmij` (Schubfach), in the notation of Rust's `{:?}` — zmij writes `[1e-5, 1e-4)` in
/// positional notation and exponents from 1e16 on with a `+`, which are rewritten here (tested
/// against `{:?}`). Where two last digits are equally short and both round-trip, zmij's choice
/// may differ from Rust's: the value read back is the same.
pub fn fmt_f64_into(v: f64, out: &mut Vec<u8>) {
    let v = v + 0.0;
    let mut b = zmij::Buffer::new();
    let text = b.format(v).as_bytes();
    let a = v.abs();
    if (1e-5..1e-4).contains(&a) {
        // "0.0000d…" (or "-0.0000d…") → "d.…e-5".
        let (sign, digits) = match text.split_first() {
            Some((b'-', rest)) => (&text[..1], rest),
            _ => (&text[..0], text),
        };
        match digits.strip_prefix(b"0.0000") {
            Some(d) if !d.is_empty() => {
                out.extend_from_slice(sign);
                out.push(d[0]);
                if d.len() > 1 {
                    out.push(b'.');
                    out.extend_from_slice(&d[1..]);
                }
                out.extend_from_slice(b"e-5");
            }
            _ => out.extend_from_slice(text),
        }
    } else if a >= 1e16 {
        out.extend(text.iter().filter(|c| **c != b'+'));
    } else {
        out.extend_from_slice(text);
    }
}

/// The project's one CSV writer: a header, then rows of fields — numbers in shortest
/// round-trip form ([`fmt_f64`]), text quoted where CSV needs it.
#[derive(Debug)]
pub struct CsvTable {
    w: csv::Writer<Vec<u8>>,
}

impl CsvTable {
    /// A table with these column names.
    pub fn new<S: AsRef<str>>(header: impl IntoIterator<Item = S>) -> Self {
        let mut t = Self {
            w: csv::Writer::from_writer(Vec::new()),
        };
        t.fields(header);
        t
    }

    /// The document of a header and rows of numbers.
    pub fn document<S: AsRef<str>, R: AsRef<[f64]>>(
        header: impl IntoIterator<Item = S>,
        rows: impl IntoIterator<Item = R>,
    ) -> Vec<u8> {
        let mut t = Self::new(header);
        for row in rows {
            t.row(row.as_ref());
        }
        t.into_bytes()
    }

    /// Appends a row of numbers.
    pub fn row(&mut self, values: &[f64]) {
        self.fields(values.iter().map(|v| fmt_f64(*v)));
    }

    /// Appends a row of text fields.
    pub fn fields<S: AsRef<str>>(&mut self, fields: impl IntoIterator<Item = S>) {
        self.w
            .write_record(fields.into_iter().map(|f| f.as_ref().to_string()))
            .expect("writing to memory cannot fail");
    }

    /// The document.
    pub fn into_bytes(self) -> Vec<u8> {
        self.w.into_inner().expect("writing to memory cannot fail")
    }
}

/// The result CSV of `polbrdf eval`: the input columns unchanged, then `brdf, dolp, aolp_deg,
/// m00 … m33` (F row-major, psps basis, sr⁻¹) for each row's result in `pbrdf`.
///
/// # Errors
/// [`Error::File`] when an input column has the name of an output column.
pub fn results_csv(table: &GeometryTable, pbrdf: &[crate::table::RowResult]) -> Result<Vec<u8>> {
    let extra = result_columns();
    if let Some(clash) = table.headers.iter().find(|h| extra.contains(h)) {
        return Err(Error::File {
            path: table.path.clone(),
            message: format!("input column `{clash}` has the name of an output column; rename it"),
        });
    }
    let mut t = CsvTable::new(table.headers.iter().chain(extra.iter()));
    for (row, f) in table.rows.iter().zip(pbrdf) {
        let mut fields: Vec<String> = row.clone();
        fields.extend(crate::table::result_values(f).iter().map(|v| fmt_f64(*v)));
        t.fields(fields);
    }
    Ok(t.into_bytes())
}

#[cfg(test)]
mod tests {
    #[test]
    fn fast_float_text_round_trips_in_rusts_notation() {
        // Every magnitude from subnormals to 1e300, with awkward mantissas.
        let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
        for e in -320..300 {
            for _ in 0..40 {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                let m = 1.0 + (x >> 11) as f64 / (1u64 << 53) as f64;
                for v in [
                    m * 10f64.powi(e),
                    -m * 10f64.powi(e),
                    10f64.powi(e),
                    5.0 * 10f64.powi(e),
                ] {
                    same_value_and_notation(v);
                }
            }
        }
        for v in [
            0.0,
            -0.0,
            1.0,
            0.1,
            1e-4,
            1e-5,
            9.99e-5,
            1e16,
            9.999e15,
            f64::MAX,
            f64::MIN_POSITIVE,
        ] {
            same_value_and_notation(v);
        }
    }

    fn same_value_and_notation(v: f64) {
        let mut b = Vec::new();
        super::fmt_f64_into(v, &mut b);
        let ours = String::from_utf8(b).unwrap();
        let rust = format!("{:?}", v + 0.0);
        assert_eq!(
            ours.parse::<f64>().unwrap().to_bits(),
            (v + 0.0).to_bits(),
            "{ours}"
        );
        assert_eq!(ours.len(), rust.len(), "{ours} vs {rust}");
        assert_eq!(ours.contains('e'), rust.contains('e'), "{ours} vs {rust}");
    }
}
