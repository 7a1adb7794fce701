//! NumPy `.npy` tables: a one-dimensional array of a structured dtype whose fields are the
//! columns, each a float (`<f8` when written; `<f8`, `>f8`, `<f4`, `>f4` when read), in C order.
//!
//! The column names are the field names, so a file is self-describing:
//! `numpy.load("out.npy")["brdf"]` is a column, and `numpy.save` of such an array is a valid
//! input. A plain 2-D array has no column names and is refused with a message saying so.
//!
//! The format (NEP 1): the magic `\x93NUMPY`, a version byte pair (1.0, 2.0 or 3.0), the
//! header's length (u16 for 1.0, u32 for 2.0 and 3.0, little-endian), the header — a Python
//! dict literal `{'descr': [...], 'fortran_order': False, 'shape': (N,), }` padded with spaces
//! and ended by a newline so that the data starts at a multiple of 64 bytes — then the rows.
//! Headers of versions 1 and 2 are Latin-1, of version 3 UTF-8; the writer picks the lowest
//! version that can hold its header, as numpy does.
//!
//! [`NpyWriter`] streams: the header first, then rows in any number of calls. When the row
//! count is not known in advance, [`NpyWriter::new_patchable`] reserves room for a 20-digit
//! count and [`NpyWriter::finish_patched`] rewrites the header in place at the end (the header's
//! length never changes).
//!
//! Images are plain arrays, not tables: [`array_f64`] and [`array_bool`] give the bytes of a
//! file holding one (e.g. the simulated camera frame of `polbrdf detect --frame`).

use crate::error::{Error, Result};
use std::io::{Read, Seek, SeekFrom, Write};
use std::path::Path;

mod header_text;
use header_text::parse_header_text;

/// The magic bytes every `.npy` file starts with.
pub const MAGIC: &[u8; 6] = b"\x93NUMPY";

/// The largest header the reader accepts (bytes). numpy's own limit is 10 000 by default; a
/// table with thousands of long column names still fits.
pub const MAX_HEADER_LEN: usize = 1 << 20;

/// The data start is aligned to this many bytes (NEP 1).
const ALIGN: usize = 64;

/// Digits reserved for the row count (`u64::MAX` has 20).
const COUNT_DIGITS: usize = 20;

/// The element type of one column as stored.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dtype {
    /// `<f8`: little-endian IEEE double.
    F8Le,
    /// `>f8`: big-endian IEEE double.
    F8Be,
    /// `<f4`: little-endian IEEE single.
    F4Le,
    /// `>f4`: big-endian IEEE single.
    F4Be,
}

impl Dtype {
    fn parse(s: &str) -> Option<Self> {
        match s {
            "<f8" => Some(Dtype::F8Le),
            ">f8" => Some(Dtype::F8Be),
            "<f4" => Some(Dtype::F4Le),
            ">f4" => Some(Dtype::F4Be),
            // `=` is native order: little-endian on every platform polbrdf builds for.
            "=f8" if cfg!(target_endian = "little") => Some(Dtype::F8Le),
            "=f4" if cfg!(target_endian = "little") => Some(Dtype::F4Le),
            _ => None,
        }
    }

    /// Bytes per element.
    pub fn size(self) -> usize {
        match self {
            Dtype::F8Le | Dtype::F8Be => 8,
            Dtype::F4Le | Dtype::F4Be => 4,
        }
    }

    fn decode(self, b: &[u8]) -> f64 {
        match self {
            Dtype::F8Le => f64::from_le_bytes(b.try_into().expect("8 bytes")),
            Dtype::F8Be => f64::from_be_bytes(b.try_into().expect("8 bytes")),
            Dtype::F4Le => f64::from(f32::from_le_bytes(b.try_into().expect("4 bytes"))),
            Dtype::F4Be => f64::from(f32::from_be_bytes(b.try_into().expect("4 bytes"))),
        }
    }
}

/// A parsed `.npy` header.
#[derive(Debug, Clone, PartialEq)]
pub struct NpyHeader {
    /// Format version (major, minor).
    pub version: (u8, u8),
    /// The column (field) names, in order.
    pub columns: Vec<String>,
    /// Each column's element type.
    pub dtypes: Vec<Dtype>,
    /// The number of rows (the array's one dimension).
    pub rows: u64,
    /// Where the data starts (bytes from the start of the file).
    pub data_offset: usize,
}

impl NpyHeader {
    /// Bytes per row.
    pub fn row_size(&self) -> usize {
        self.dtypes.iter().map(|d| d.size()).sum()
    }

    /// Bytes of data the header announces (`None` if that overflows).
    pub fn data_len(&self) -> Option<u64> {
        self.rows.checked_mul(self.row_size() as u64)
    }
}

fn file_err(path: &Path, message: impl Into<String>) -> Error {
    Error::File {
        path: path.to_path_buf(),
        message: message.into(),
    }
}

/// Reads the preamble (magic, version, header length) and the header from `r`.
///
/// # Errors
/// [`Error::Read`] for an I/O error, [`Error::File`] for a file that is not `.npy`, a
/// truncated or malformed header, an unsupported dtype, shape or order.
pub fn read_header<R: Read>(r: &mut R, path: &Path) -> Result<NpyHeader> {
    let mut pre = [0u8; 8];
    let mut got = 0;
    while got < pre.len() {
        match r.read(&mut pre[got..]) {
            Ok(0) => break,
            Ok(k) => got += k,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => {
                return Err(Error::Read {
                    path: path.to_path_buf(),
                    source: e,
                })
            }
        }
    }
    if !MAGIC.starts_with(&pre[..got.min(6)]) || got == 0 {
        return Err(file_err(
            path,
            "not a .npy file (it does not start with \\x93NUMPY)",
        ));
    }
    if got < pre.len() {
        return Err(file_err(path, "the file ends inside the .npy preamble"));
    }
    if &pre[..6] != MAGIC {
        return Err(file_err(
            path,
            "not a .npy file (it does not start with \\x93NUMPY)",
        ));
    }
    let version = (pre[6], pre[7]);
    let (len, pre_len) = match version {
        (1, 0) => {
            let mut b = [0u8; 2];
            read_exact_or(r, &mut b, path, "the file ends inside the .npy preamble")?;
            (usize::from(u16::from_le_bytes(b)), 10)
        }
        (2, 0) | (3, 0) => {
            let mut b = [0u8; 4];
            read_exact_or(r, &mut b, path, "the file ends inside the .npy preamble")?;
            (u32::from_le_bytes(b) as usize, 12)
        }
        (a, b) => {
            return Err(file_err(
                path,
                format!(".npy format version {a}.{b} is not supported (1.0, 2.0 and 3.0 are)"),
            ))
        }
    };
    if len > MAX_HEADER_LEN {
        return Err(file_err(
            path,
            format!(".npy header of {len} bytes is longer than the limit of {MAX_HEADER_LEN}"),
        ));
    }
    let mut header = vec![0u8; len];
    read_exact_or(r, &mut header, path, "the file ends inside the .npy header")?;
    let text: String = if version.0 == 3 {
        String::from_utf8(header)
            .map_err(|_| file_err(path, ".npy version 3 header is not valid UTF-8"))?
    } else {
        // Latin-1: every byte is the code point of the same value.
        header.iter().map(|&b| char::from(b)).collect()
    };
    let mut h = parse_header_text(&text, path)?;
    h.version = version;
    h.data_offset = pre_len + len;
    Ok(h)
}

fn read_exact_or<R: Read>(r: &mut R, buf: &mut [u8], path: &Path, what: &str) -> Result<()> {
    r.read_exact(buf).map_err(|e| {
        if e.kind() == std::io::ErrorKind::UnexpectedEof {
            file_err(path, what)
        } else {
            Error::Read {
                path: path.to_path_buf(),
                source: e,
            }
        }
    })
}

/// A whole `.npy` table in memory.
#[derive(Debug, Clone, PartialEq)]
pub struct NpyTable {
    /// Column names.
    pub columns: Vec<String>,
    /// The values, row-major (`rows × columns.len()`).
    pub data: Vec<f64>,
}

impl NpyTable {
    /// The number of rows.
    pub fn rows(&self) -> usize {
        self.data.len().checked_div(self.columns.len()).unwrap_or(0)
    }
}

/// Parses the bytes of a `.npy` table; `path` is used in messages only.
///
/// # Errors
/// As [`read_header`], and [`Error::File`] when the data is shorter or longer than the
/// header's shape says.
pub fn parse_npy(bytes: &[u8], path: &Path) -> Result<NpyTable> {
    let mut r = bytes;
    let h = read_header(&mut r, path)?;
    let need = h.data_len();
    if need != Some(r.len() as u64) {
        return Err(size_mismatch(path, &h, r.len() as u64));
    }
    let mut reader = NpyReader {
        header: h,
        r,
        path: path.to_path_buf(),
        rows_read: 0,
        buf: Vec::new(),
    };
    let mut data = Vec::new();
    while reader.read_rows(usize::MAX, &mut data)? > 0 {}
    Ok(NpyTable {
        columns: reader.header.columns,
        data,
    })
}

fn size_mismatch(path: &Path, h: &NpyHeader, have: u64) -> Error {
    let need = match h.data_len() {
        Some(n) => format!("{n} bytes"),
        None => "more bytes than a file can hold".into(),
    };
    file_err(
        path,
        format!(
            ".npy data is {have} bytes, but the header's shape ({},) of {}-byte rows needs {need}",
            h.rows,
            h.row_size()
        ),
    )
}

/// Reads a `.npy` table (`-` = standard input).
///
/// # Errors
/// As [`parse_npy`], and [`Error::Read`].
pub fn read_npy(path: &Path) -> Result<NpyTable> {
    parse_npy(&crate::csv_io::read_all(path)?, path)
}

/// A streaming reader of a `.npy` table: the header, then rows in chunks.
#[derive(Debug)]
pub struct NpyReader<R> {
    header: NpyHeader,
    r: R,
    path: std::path::PathBuf,
    rows_read: u64,
    buf: Vec<u8>,
}

impl<R: Read> NpyReader<R> {
    /// Reads the header from `r`; `path` is used in messages.
    ///
    /// # Errors
    /// As [`read_header`].
    pub fn new(mut r: R, path: &Path) -> Result<Self> {
        let header = read_header(&mut r, path)?;
        Ok(Self {
            header,
            r,
            path: path.to_path_buf(),
            rows_read: 0,
            buf: Vec::new(),
        })
    }

    /// The header.
    pub fn header(&self) -> &NpyHeader {
        &self.header
    }

    /// Rows read so far.
    pub fn rows_read(&self) -> u64 {
        self.rows_read
    }

    /// Appends up to `max` rows to `out` (row-major, as f64) and returns how many; 0 at the
    /// end. After the last row it checks that the data ends there.
    ///
    /// # Errors
    /// [`Error::Read`], or [`Error::File`] when the data ends early or goes on after the last
    /// row.
    pub fn read_rows(&mut self, max: usize, out: &mut Vec<f64>) -> Result<usize> {
        let left = self.header.rows - self.rows_read;
        let row = self.header.row_size();
        // At most 8 MiB per call.
        let n = (max as u64)
            .min(left)
            .min((8 << 20) / row.max(1) as u64 + 1) as usize;
        if n == 0 {
            if left == 0 {
                // The data must end with the last row.
                let mut extra = [0u8; 1];
                match self.r.read(&mut extra) {
                    Ok(0) => {}
                    Ok(_) => {
                        return Err(file_err(
                            &self.path,
                            format!(
                                ".npy data goes on after the {} rows of the header's shape",
                                self.header.rows
                            ),
                        ))
                    }
                    Err(e) => {
                        return Err(Error::Read {
                            path: self.path.clone(),
                            source: e,
                        })
                    }
                }
            }
            return Ok(0);
        }
        self.buf.resize(n * row, 0);
        let mut got = 0;
        while got < self.buf.len() {
            match self.r.read(&mut self.buf[got..]) {
                Ok(0) => {
                    let have = self.rows_read * row as u64 + got as u64;
                    return Err(size_mismatch(&self.path, &self.header, have));
                }
                Ok(k) => got += k,
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
                Err(e) => {
                    return Err(Error::Read {
                        path: self.path.clone(),
                        source: e,
                    })
                }
            }
        }
        out.reserve(n * self.header.columns.len());
        for rec in self.buf.chunks_exact(row) {
            let mut at = 0;
            for d in &self.header.dtypes {
                out.push(d.decode(&rec[at..at + d.size()]));
                at += d.size();
            }
        }
        self.rows_read += n as u64;
        if max > n && self.rows_read == self.header.rows {
            // Asked for more than there was: check the end now.
            self.read_rows(0, out)?;
        }
        Ok(n)
    }
}

/// The Python `repr` of a string, single-quoted (what `ast.literal_eval` reads back).
fn py_str(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('\'');
    for c in s.chars() {
        match c {
            '\\' => out.push_str("\\\\"),
            '\'' => out.push_str("\\'"),
            c if (c as u32) < 0x20 || c as u32 == 0x7f => {
                out.push_str(&format!("\\x{:02x}", c as u32));
            }
            c => out.push(c),
        }
    }
    out.push('\'');
    out
}

/// The full header block (magic to newline) for these columns and row count.
fn header_block(columns: &[String], rows: u64) -> Vec<u8> {
    let descr: Vec<String> = columns
        .iter()
        .map(|c| format!("({}, '<f8')", py_str(c)))
        .collect();
    let count = rows.to_string();
    // Room for the longest count, so a later count fits in the same length.
    let spare = COUNT_DIGITS - count.len();
    let dict = format!(
        "{{'descr': [{}], 'fortran_order': False, 'shape': ({count},), }}",
        descr.join(", ")
    );
    padded_header(&dict, spare)
}

/// The header block (magic to newline) around a header dict, with room for `spare` more
/// characters: the lowest version that holds it, padded so the data starts at a multiple of
/// 64 bytes.
fn padded_header(dict: &str, spare: usize) -> Vec<u8> {
    let latin1 = dict.chars().all(|c| (c as u32) < 0x100);
    let body_len = |pre: usize| {
        let unpadded = pre + encoded_len(dict, latin1) + spare + 1;
        unpadded.div_ceil(ALIGN) * ALIGN - pre
    };
    let (version, pre) = if !latin1 {
        (3u8, 12)
    } else if body_len(10) <= usize::from(u16::MAX) {
        (1, 10)
    } else {
        (2, 12)
    };
    let len = body_len(pre);
    let mut out = Vec::with_capacity(pre + len);
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&[version, 0]);
    if version == 1 {
        out.extend_from_slice(&(len as u16).to_le_bytes());
    } else {
        out.extend_from_slice(&(len as u32).to_le_bytes());
    }
    if latin1 {
        out.extend(dict.chars().map(|c| c as u8));
    } else {
        out.extend_from_slice(dict.as_bytes());
    }
    out.resize(pre + len - 1, b' ');
    out.push(b'\n');
    out
}

fn encoded_len(s: &str, latin1: bool) -> usize {
    if latin1 {
        s.chars().count()
    } else {
        s.len()
    }
}

/// The bytes of a `.npy` file holding a plain array of the given shape (C order), of `<f8`
/// values (`numpy.load` gives a `float64` array of that shape) — for images, not tables.
///
/// # Errors
/// `InvalidInput` when the shape's product is not the number of values.
pub fn array_f64(shape: &[usize], values: &[f64]) -> std::io::Result<Vec<u8>> {
    let mut out = array_header(shape, values.len(), "<f8")?;
    out.reserve(values.len() * 8);
    for v in values {
        out.extend_from_slice(&v.to_le_bytes());
    }
    Ok(out)
}

/// The bytes of a `.npy` file holding a plain boolean array (`|b1`, one byte 0 or 1 per value)
/// of the given shape (C order).
///
/// # Errors
/// `InvalidInput` when the shape's product is not the number of values.
pub fn array_bool(shape: &[usize], values: &[bool]) -> std::io::Result<Vec<u8>> {
    let mut out = array_header(shape, values.len(), "|b1")?;
    out.extend(values.iter().map(|&b| u8::from(b)));
    Ok(out)
}

fn array_header(shape: &[usize], len: usize, descr: &str) -> std::io::Result<Vec<u8>> {
    let count = shape.iter().try_fold(1usize, |a, &n| a.checked_mul(n));
    if count != Some(len) {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            format!("{len} values do not fill an array of shape {shape:?}"),
        ));
    }
    let dims: Vec<String> = shape.iter().map(usize::to_string).collect();
    let shape = match dims.len() {
        1 => format!("({},)", dims[0]),
        _ => format!("({})", dims.join(", ")),
    };
    let dict = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}");
    Ok(padded_header(&dict, 0))
}

/// A streaming `.npy` writer of a table of `<f8` columns.
#[derive(Debug)]
pub struct NpyWriter<W: Write> {
    w: W,
    columns: Vec<String>,
    /// The count in the header (`None`: to be patched at the end).
    declared: Option<u64>,
    /// Where the header starts, for patching.
    start: u64,
    header_len: usize,
    rows: u64,
    buf: Vec<u8>,
}

/// Checks column names for a structured dtype: non-empty and distinct.
pub(crate) fn check_columns<S: AsRef<str>>(columns: &[S]) -> std::io::Result<Vec<String>> {
    let invalid = |m: String| std::io::Error::new(std::io::ErrorKind::InvalidInput, m);
    if columns.is_empty() {
        return Err(invalid("a .npy table needs at least one column".into()));
    }
    let mut out: Vec<String> = Vec::with_capacity(columns.len());
    let mut seen = std::collections::HashSet::with_capacity(columns.len());
    for c in columns {
        let c = c.as_ref();
        if c.is_empty() {
            return Err(invalid(
                "a column has an empty name (a .npy field needs one)".into(),
            ));
        }
        if !seen.insert(c) {
            return Err(invalid(format!("column `{c}` appears twice")));
        }
        out.push(c.to_string());
    }
    Ok(out)
}

impl<W: Write> NpyWriter<W> {
    /// Starts a table of `rows` rows: writes the header. [`finish`](Self::finish) checks that
    /// exactly `rows` rows were written.
    ///
    /// # Errors
    /// `InvalidInput` for no column, an empty or a repeated column name; the writer's error.
    pub fn new<S: AsRef<str>>(mut w: W, columns: &[S], rows: u64) -> std::io::Result<Self> {
        let columns = check_columns(columns)?;
        let h = header_block(&columns, rows);
        w.write_all(&h)?;
        Ok(Self {
            w,
            columns,
            declared: Some(rows),
            start: 0,
            header_len: h.len(),
            rows: 0,
            buf: Vec::new(),
        })
    }

    /// The column names.
    pub fn columns(&self) -> &[String] {
        &self.columns
    }

    /// The underlying writer.
    pub fn get_ref(&self) -> &W {
        &self.w
    }

    /// True for a table started with [`new_patchable`](Self::new_patchable).
    pub fn is_patchable(&self) -> bool {
        self.declared.is_none()
    }

    /// Rows written so far.
    pub fn rows_written(&self) -> u64 {
        self.rows
    }

    /// Writes rows given row-major (`values.len()` a multiple of the column count).
    ///
    /// # Errors
    /// `InvalidInput` when the length is not a multiple of the column count; the writer's
    /// error.
    pub fn write_rows(&mut self, values: &[f64]) -> std::io::Result<()> {
        let c = self.columns.len();
        if !values.len().is_multiple_of(c) {
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                format!("{} values are not whole rows of {c} columns", values.len()),
            ));
        }
        self.buf.clear();
        self.buf.reserve(values.len() * 8);
        for v in values {
            self.buf.extend_from_slice(&v.to_le_bytes());
        }
        self.w.write_all(&self.buf)?;
        self.rows += (values.len() / c) as u64;
        Ok(())
    }

    /// Ends a table started with [`new`](Self::new): flushes and returns the writer.
    ///
    /// # Errors
    /// `InvalidData` when the number of rows written differs from the header's, or the table
    /// was started with [`new_patchable`](Self::new_patchable) (use
    /// [`finish_patched`](Self::finish_patched)); the writer's error.
    pub fn finish(mut self) -> std::io::Result<W> {
        match self.declared {
            Some(n) if n == self.rows => {
                self.w.flush()?;
                Ok(self.w)
            }
            Some(n) => Err(std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                format!("{} rows written, the .npy header says {n}", self.rows),
            )),
            None => Err(std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                "the row count is to be patched: use finish_patched",
            )),
        }
    }
}

impl<W: Write + Seek> NpyWriter<W> {
    /// Starts a table whose row count is not known yet, at the writer's current position: the
    /// header reserves room for any count, [`finish_patched`](Self::finish_patched) fills it in.
    ///
    /// # Errors
    /// As [`new`](Self::new), and the writer's seek error.
    pub fn new_patchable<S: AsRef<str>>(mut w: W, columns: &[S]) -> std::io::Result<Self> {
        let columns = check_columns(columns)?;
        let start = w.stream_position()?;
        let h = header_block(&columns, 0);
        w.write_all(&h)?;
        Ok(Self {
            w,
            columns,
            declared: None,
            start,
            header_len: h.len(),
            rows: 0,
            buf: Vec::new(),
        })
    }

    /// Ends the table: rewrites the header with the number of rows written (same length),
    /// leaves the writer positioned after the data, flushes and returns it.
    ///
    /// # Errors
    /// The writer's error.
    pub fn finish_patched(mut self) -> std::io::Result<W> {
        let h = header_block(&self.columns, self.rows);
        debug_assert_eq!(h.len(), self.header_len);
        let end = self.w.stream_position()?;
        self.w.seek(SeekFrom::Start(self.start))?;
        self.w.write_all(&h)?;
        self.w.seek(SeekFrom::Start(end))?;
        self.w.flush()?;
        Ok(self.w)
    }
}

/// The bytes of a whole `.npy` table (`data` row-major).
///
/// # Errors
/// As [`NpyWriter::new`] and [`NpyWriter::write_rows`].
pub fn npy_bytes<S: AsRef<str>>(columns: &[S], data: &[f64]) -> std::io::Result<Vec<u8>> {
    let rows = data.len().checked_div(columns.len()).unwrap_or(0) as u64;
    let mut w = NpyWriter::new(Vec::new(), columns, rows)?;
    w.write_rows(data)?;
    w.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p() -> &'static Path {
        Path::new("t.npy")
    }

    #[test]
    fn round_trip_and_alignment() {
        let cols = ["a", "b'c", "µm"];
        let data = [1.0, -2.5, 3e-300, f64::MAX, 0.0, -0.0];
        let bytes = npy_bytes(&cols, &data).unwrap();
        let h = read_header(&mut &bytes[..], p()).unwrap();
        assert_eq!(h.version, (1, 0));
        assert_eq!(h.data_offset % ALIGN, 0);
        assert_eq!(h.rows, 2);
        let t = parse_npy(&bytes, p()).unwrap();
        assert_eq!(t.columns, cols);
        assert_eq!(
            t.data.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
            data.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
        );
    }

    #[test]
    fn plain_arrays_have_numpys_header_and_c_order_data() {
        let values = [1.0, -2.0, 0.5, f64::NAN, 3.0, 4.0];
        let bytes = array_f64(&[2, 3], &values).unwrap();
        let text = String::from_utf8_lossy(&bytes[10..]).to_string();
        assert!(text.starts_with("{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }"));
        let offset = bytes.len() - 8 * values.len();
        assert_eq!(offset % ALIGN, 0);
        assert_eq!(bytes[offset - 1], b'\n');
        let back: Vec<u64> = bytes[offset..]
            .chunks(8)
            .map(|c| u64::from_le_bytes(c.try_into().unwrap()))
            .collect();
        assert_eq!(back, values.map(f64::to_bits));
        // The table reader refuses it as a plain array, having parsed the header.
        let e = parse_npy(&bytes, p()).unwrap_err().to_string();
        assert!(e.contains("plain dtype `<f8` and shape [2, 3]"), "{e}");

        let mask = array_bool(&[3], &[true, false, true]).unwrap();
        assert!(String::from_utf8_lossy(&mask)
            .contains("{'descr': '|b1', 'fortran_order': False, 'shape': (3,), }"));
        assert_eq!(&mask[mask.len() - 3..], &[1, 0, 1]);
        assert!(array_f64(&[2, 2], &values).is_err());
        assert!(array_bool(&[usize::MAX, 2], &[]).is_err());
    }

    #[test]
    fn non_latin1_names_use_version_3() {
        let bytes = npy_bytes(&["θ_i"], &[1.0]).unwrap();
        assert_eq!(&bytes[6..8], &[3, 0]);
        assert_eq!(parse_npy(&bytes, p()).unwrap().columns, ["θ_i"]);
    }

    #[test]
    fn patched_count_keeps_the_header_length() {
        let mut w =
            NpyWriter::new_patchable(std::io::Cursor::new(Vec::new()), &["x", "y"]).unwrap();
        for k in 0..1000 {
            w.write_rows(&[f64::from(k), -f64::from(k)]).unwrap();
        }
        let bytes = w.finish_patched().unwrap().into_inner();
        let t = parse_npy(&bytes, p()).unwrap();
        assert_eq!(t.rows(), 1000);
        assert_eq!(t.data[1999], -999.0);
        assert_eq!(
            header_block(&t.columns, 0).len(),
            header_block(&t.columns, u64::MAX).len()
        );
    }

    #[test]
    fn wrong_row_count_is_an_error() {
        let mut w = NpyWriter::new(Vec::new(), &["x"], 2).unwrap();
        w.write_rows(&[1.0]).unwrap();
        assert!(w.finish().is_err());
        assert!(NpyWriter::new(Vec::new(), &["x", "x"], 0).is_err());
        assert!(NpyWriter::new(Vec::new(), &[""], 0).is_err());
    }

    fn with_header(dict: &str, data: &[u8]) -> Vec<u8> {
        let mut b = MAGIC.to_vec();
        b.extend_from_slice(&[1, 0]);
        b.extend_from_slice(&(dict.len() as u16 + 1).to_le_bytes());
        b.extend_from_slice(dict.as_bytes());
        b.push(b'\n');
        b.extend_from_slice(data);
        b
    }

    fn err(bytes: &[u8]) -> String {
        let e = parse_npy(bytes, p()).unwrap_err().to_string();
        assert!(e.starts_with("t.npy: "), "{e}");
        e
    }

    #[test]
    fn reads_numpy_variants() {
        // Big-endian and single precision, double quotes, no trailing commas.
        let mut data = 1.5f64.to_be_bytes().to_vec();
        data.extend_from_slice(&2.25f32.to_le_bytes());
        let b = with_header(
            "{\"descr\": [(\"x\", \">f8\"), ('y', '<f4')], 'fortran_order': False, 'shape': (1,)}",
            &data,
        );
        assert_eq!(parse_npy(&b, p()).unwrap().data, [1.5, 2.25]);
    }

    #[test]
    fn bad_headers_are_named() {
        let d = 1.0f64.to_le_bytes();
        assert!(err(b"PK\x03\x04").contains("not a .npy file"));
        assert!(err(b"\x93NUMPY\x01").contains("preamble"));
        assert!(err(b"\x93NUMPY\x04\x00\x00\x00").contains("version 4.0"));
        let cases = [
            ("{'descr': '<f8', 'fortran_order': False, 'shape': (1, 1), }", "named columns"),
            ("{'descr': [('x', '<i8')], 'fortran_order': False, 'shape': (1,), }", "<i8"),
            ("{'descr': [('x', '<f8')], 'fortran_order': True, 'shape': (1,), }", "Fortran"),
            ("{'descr': [('x', '<f8')], 'fortran_order': False, 'shape': (1, 2), }", "one-dimensional"),
            ("{'descr': [('x', '<f8'), ('x', '<f8')], 'fortran_order': False, 'shape': (1,), }", "twice"),
            ("{'descr': [('x', '<f8')], 'shape': (1,), }", "required"),
            ("{'descr': [('x', '<f8')], 'fortran_order': False, 'shape': (1,), 'x': 1}", "unknown key"),
            ("{'descr': [('x', '<f8', (2,))], 'fortran_order': False, 'shape': (1,), }", "sub-array"),
            ("{'descr': [('x', '<f8')], 'fortran_order': False, 'shape': (99999999999999999999999,), }", "too large"),
            ("{'descr': [('x, '<f8')], 'fortran_order': False, 'shape': (1,), }", "expected"),
            ("{'descr': [('x', '<f8')], 'fortran_order': False, 'shape': (1,), } junk", "after"),
            ("[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[", "deeply"),
        ];
        for (h, want) in cases {
            let e = err(&with_header(h, &d));
            assert!(e.contains(want), "{h}: {e}");
        }
        let ok = "{'descr': [('x', '<f8')], 'fortran_order': False, 'shape': (2,), }";
        assert!(err(&with_header(ok, &d)).contains("needs 16 bytes"));
        let mut long = d.to_vec();
        long.extend_from_slice(&d);
        long.push(0);
        assert!(err(&with_header(ok, &long)).contains("is 17 bytes"));
        let huge =
            "{'descr': [('x', '<f8')], 'fortran_order': False, 'shape': (18446744073709551615,), }";
        assert!(err(&with_header(huge, &d)).contains("more bytes than"));
    }

    #[test]
    fn streaming_reader_detects_truncation_and_trailing_bytes() {
        let bytes = npy_bytes(&["x"], &[1.0, 2.0, 3.0]).unwrap();
        let mut r = NpyReader::new(&bytes[..bytes.len() - 3], p()).unwrap();
        let mut out = Vec::new();
        assert!(r
            .read_rows(10, &mut out)
            .unwrap_err()
            .to_string()
            .contains("needs 24"));
        let mut extra = bytes.clone();
        extra.push(1);
        let mut r = NpyReader::new(&extra[..], p()).unwrap();
        out.clear();
        assert!(r.read_rows(10, &mut out).is_err());
        let mut r = NpyReader::new(&bytes[..], p()).unwrap();
        out.clear();
        assert_eq!(r.read_rows(2, &mut out).unwrap(), 2);
        assert_eq!(r.read_rows(2, &mut out).unwrap(), 1);
        assert_eq!(r.read_rows(2, &mut out).unwrap(), 0);
        assert_eq!(out, [1.0, 2.0, 3.0]);
    }
}
