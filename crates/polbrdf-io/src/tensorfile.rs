//! Mitsuba 3 TensorFiles (`.pbsdf` of the `measured_polarized` plugin; docs/model.md §20),
//! read streamed (`Read + Seek`, bounded memory) and written atomically.
//!
//! Layout (little endian; Mitsuba's `src/core/tensor.cpp`): the 12 bytes `tensor_file\0`, the
//! version `1, 0` (two bytes), the field count (u32), then per field: name length (u16), name
//! (UTF-8), number of dimensions (u16), dtype (u8: 1 u8, 2 i8, 3 u16, 4 i16, 5 u32, 6 i32,
//! 7 u64, 8 i64, 9 f16, 10 f32, 11 f64), data offset from the file start (u64), shape (u64 each);
//! then the data of each field, C order.

use crate::error::{Error, Result};
use std::fs::File;
use std::io::{BufReader, Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

/// The file's first 12 bytes.
pub const MAGIC: &[u8; 12] = b"tensor_file\0";

/// Element types of a TensorFile field (Mitsuba's `Struct::Type` codes 1–11).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dtype {
    /// 1
    U8,
    /// 2
    I8,
    /// 3
    U16,
    /// 4
    I16,
    /// 5
    U32,
    /// 6
    I32,
    /// 7
    U64,
    /// 8
    I64,
    /// 9
    F16,
    /// 10
    F32,
    /// 11
    F64,
}

impl Dtype {
    /// From the file's code.
    pub fn from_code(c: u8) -> Option<Self> {
        use Dtype::*;
        Some(match c {
            1 => U8,
            2 => I8,
            3 => U16,
            4 => I16,
            5 => U32,
            6 => I32,
            7 => U64,
            8 => I64,
            9 => F16,
            10 => F32,
            11 => F64,
            _ => return None,
        })
    }

    /// The file's code.
    pub fn code(self) -> u8 {
        self as u8 + 1
    }

    /// Bytes per element.
    pub fn size(self) -> u64 {
        use Dtype::*;
        match self {
            U8 | I8 => 1,
            U16 | I16 | F16 => 2,
            U32 | I32 | F32 => 4,
            U64 | I64 | F64 => 8,
        }
    }

    /// Name as in numpy.
    pub fn name(self) -> &'static str {
        use Dtype::*;
        match self {
            U8 => "uint8",
            I8 => "int8",
            U16 => "uint16",
            I16 => "int16",
            U32 => "uint32",
            I32 => "int32",
            U64 => "uint64",
            I64 => "int64",
            F16 => "float16",
            F32 => "float32",
            F64 => "float64",
        }
    }
}

/// One field's header.
#[derive(Debug, Clone, PartialEq)]
pub struct Field {
    /// Its name.
    pub name: String,
    /// Element type.
    pub dtype: Dtype,
    /// Byte offset of its data from the start of the file.
    pub offset: u64,
    /// Shape (C order).
    pub shape: Vec<u64>,
}

impl Field {
    /// Number of elements.
    pub fn len(&self) -> u64 {
        self.shape.iter().product()
    }

    /// True when it has no element.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// An open TensorFile: its validated header; data read on demand.
#[derive(Debug)]
pub struct TensorFile {
    path: PathBuf,
    reader: BufReader<File>,
    size: u64,
    fields: Vec<Field>,
}

fn bad(path: &Path, message: String) -> Error {
    Error::File {
        path: path.to_path_buf(),
        message: format!("not a valid TensorFile: {message}"),
    }
}

fn field_err(path: &Path, field: &str, message: String) -> Error {
    Error::File {
        path: path.to_path_buf(),
        message: format!("TensorFile field `{field}`: {message}"),
    }
}

/// Header parser over a byte slice of the header region.
struct Cursor<'a> {
    bytes: &'a [u8],
    pos: usize,
    path: &'a Path,
}

impl Cursor<'_> {
    fn take(&mut self, n: usize, what: &str) -> Result<&[u8]> {
        let end = self.pos.checked_add(n).filter(|&e| e <= self.bytes.len());
        match end {
            Some(end) => {
                let s = &self.bytes[self.pos..end];
                self.pos = end;
                Ok(s)
            }
            None => Err(bad(
                self.path,
                format!(
                    "truncated header: {what} at byte {} runs past the end of the file",
                    self.pos
                ),
            )),
        }
    }
    fn u8(&mut self, what: &str) -> Result<u8> {
        Ok(self.take(1, what)?[0])
    }
    fn u16(&mut self, what: &str) -> Result<u16> {
        Ok(u16::from_le_bytes(
            self.take(2, what)?.try_into().expect("2 bytes"),
        ))
    }
    fn u32(&mut self, what: &str) -> Result<u32> {
        Ok(u32::from_le_bytes(
            self.take(4, what)?.try_into().expect("4 bytes"),
        ))
    }
    fn u64(&mut self, what: &str) -> Result<u64> {
        Ok(u64::from_le_bytes(
            self.take(8, what)?.try_into().expect("8 bytes"),
        ))
    }
}

/// Most bytes of header read (names and shapes of many fields fit well within).
const MAX_HEADER: u64 = 1 << 20;
/// Most fields accepted.
const MAX_FIELDS: u32 = 4096;
/// Most dimensions of a field.
const MAX_NDIM: u16 = 32;

/// Parses and validates a header from the bytes at the start of a file of `size` bytes: magic,
/// version, dtypes, shapes (no overflow), every field's data inside the file, after the header
/// and not overlapping another's, names unique and UTF-8.
///
/// # Errors
/// [`Error::File`] naming the file, the field and what is wrong.
pub fn parse_header(bytes: &[u8], size: u64, path: &Path) -> Result<(Vec<Field>, u64)> {
    let mut c = Cursor {
        bytes,
        pos: 0,
        path,
    };
    let n = preamble(&mut c, size)?;
    let mut fields: Vec<Field> = Vec::new();
    for k in 0..n {
        let field = read_field(&mut c, k, &fields)?;
        fields.push(field);
    }
    let header_end = c.pos as u64;
    check_spans(&fields, header_end, size, path)?;
    Ok((fields, header_end))
}

/// The header's start, for a file of `size` bytes: the magic, the version (1.0) and the field
/// count (at most [`MAX_FIELDS`]), which it returns.
fn preamble(c: &mut Cursor<'_>, size: u64) -> Result<u32> {
    let path = c.path;
    if c.bytes.len() < 12 {
        return Err(bad(
            path,
            format!(
                "{} bytes: too short for the 18-byte header (truncated?)",
                size
            ),
        ));
    }
    let magic = c.take(12, "magic")?;
    if magic != MAGIC {
        return Err(bad(
            path,
            "wrong magic: it does not start with `tensor_file\\0`".into(),
        ));
    }
    let version = [c.u8("version")?, c.u8("version")?];
    if version != [1, 0] {
        return Err(bad(
            path,
            format!(
                "unsupported version {}.{} (only 1.0 is known)",
                version[0], version[1]
            ),
        ));
    }
    let n = c.u32("field count")?;
    if n > MAX_FIELDS {
        return Err(bad(path, format!("{n} fields (more than {MAX_FIELDS})")));
    }
    Ok(n)
}

/// Field `k` of the header, after `fields`: its name (UTF-8, not one of theirs), number of
/// dimensions (at most [`MAX_NDIM`]), dtype code, data offset and shape.
fn read_field(c: &mut Cursor<'_>, k: u32, fields: &[Field]) -> Result<Field> {
    let path = c.path;
    let what = format!("field {k}");
    let len = c.u16(&format!("{what}: name length"))?;
    let name = std::str::from_utf8(c.take(len as usize, &format!("{what}: name"))?)
        .map_err(|_| bad(path, format!("{what}: name is not UTF-8")))?
        .to_string();
    if fields.iter().any(|f| f.name == name) {
        return Err(field_err(path, &name, "appears twice".into()));
    }
    let ndim = c.u16(&format!("field `{name}`: ndim"))?;
    if ndim > MAX_NDIM {
        return Err(field_err(
            path,
            &name,
            format!("{ndim} dimensions (more than {MAX_NDIM})"),
        ));
    }
    let code = c.u8(&format!("field `{name}`: dtype"))?;
    let dtype = Dtype::from_code(code).ok_or_else(|| {
        field_err(
            path,
            &name,
            format!("unknown dtype code {code} (1–11 are defined)"),
        )
    })?;
    let offset = c.u64(&format!("field `{name}`: offset"))?;
    let mut shape = Vec::with_capacity(ndim as usize);
    for _ in 0..ndim {
        shape.push(c.u64(&format!("field `{name}`: shape"))?);
    }
    Ok(Field {
        name,
        dtype,
        offset,
        shape,
    })
}

/// Every field's data inside the file of `size` bytes, after the header (which ends at
/// `header_end`) and not overlapping another field's; shapes that overflow are errors.
fn check_spans(fields: &[Field], header_end: u64, size: u64, path: &Path) -> Result<()> {
    let mut spans = Vec::new();
    for f in fields {
        let bytes = f
            .shape
            .iter()
            .try_fold(f.dtype.size(), |a, &d| a.checked_mul(d))
            .ok_or_else(|| field_err(path, &f.name, format!("shape {:?} overflows", f.shape)))?;
        let end = f.offset.checked_add(bytes).filter(|&e| e <= size).ok_or_else(|| {
            field_err(
                path,
                &f.name,
                format!(
                    "shape {:?} × {} ({} bytes) at offset {} runs past the end of the file ({} bytes): truncated or inconsistent shape",
                    f.shape,
                    f.dtype.name(),
                    bytes,
                    f.offset,
                    size
                ),
            )
        })?;
        if bytes > 0 && f.offset < header_end {
            return Err(field_err(
                path,
                &f.name,
                format!(
                    "data at offset {} overlaps the header (which ends at {header_end})",
                    f.offset
                ),
            ));
        }
        spans.push((f.offset, end, f.name.as_str()));
    }
    spans.retain(|s| s.1 > s.0);
    spans.sort();
    for w in spans.windows(2) {
        if w[1].0 < w[0].1 {
            return Err(field_err(
                path,
                w[1].2,
                format!("data overlaps field `{}`", w[0].2),
            ));
        }
    }
    Ok(())
}

impl TensorFile {
    /// Opens `path` and validates its header ([`parse_header`]); no data is read.
    ///
    /// # Errors
    /// [`Error::Read`], or [`Error::File`] for a malformed file.
    pub fn open(path: &Path) -> Result<Self> {
        let rd = |source| Error::Read {
            path: path.to_path_buf(),
            source,
        };
        let file = File::open(path).map_err(rd)?;
        let size = file.metadata().map_err(rd)?.len();
        let mut reader = BufReader::with_capacity(1 << 16, file);
        let mut head = Vec::new();
        (&mut reader)
            .take(size.min(MAX_HEADER))
            .read_to_end(&mut head)
            .map_err(rd)?;
        let (fields, _) = parse_header(&head, size, path)?;
        Ok(Self {
            path: path.to_path_buf(),
            reader,
            size,
            fields,
        })
    }

    /// The file.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Its size in bytes.
    pub fn size(&self) -> u64 {
        self.size
    }

    /// The fields, in header order.
    pub fn fields(&self) -> &[Field] {
        &self.fields
    }

    /// The field called `name`.
    ///
    /// # Errors
    /// [`Error::File`] when there is none.
    pub fn field(&self, name: &str) -> Result<&Field> {
        self.fields
            .iter()
            .find(|f| f.name == name)
            .ok_or_else(|| field_err(&self.path, name, "missing".into()))
    }

    /// Reads `out.len()` bytes of field `name` starting at element `start`.
    ///
    /// # Errors
    /// [`Error::Read`], or [`Error::File`] when the range is outside the field.
    pub fn read_bytes(&mut self, name: &str, start: u64, out: &mut [u8]) -> Result<()> {
        let f = self.field(name)?.clone();
        let total = f.len() * f.dtype.size();
        let from = start * f.dtype.size();
        if from + out.len() as u64 > total {
            return Err(field_err(
                &self.path,
                name,
                "read past the field's end".into(),
            ));
        }
        let rd = |source| Error::Read {
            path: self.path.clone(),
            source,
        };
        self.reader
            .seek(SeekFrom::Start(f.offset + from))
            .map_err(rd)?;
        self.reader.read_exact(out).map_err(rd)
    }

    /// Reads `n` float32 elements of field `name` from element `start`, as f64.
    ///
    /// # Errors
    /// As [`TensorFile::read_bytes`]; [`Error::File`] when the field is not float32.
    pub fn read_f32(&mut self, name: &str, start: u64, n: usize) -> Result<Vec<f64>> {
        self.expect_dtype(name, Dtype::F32)?;
        let mut b = vec![0u8; n * 4];
        self.read_bytes(name, start, &mut b)?;
        Ok(b.chunks_exact(4)
            .map(|c| f32::from_le_bytes(c.try_into().expect("4 bytes")) as f64)
            .collect())
    }

    /// Reads all of a uint16 field.
    ///
    /// # Errors
    /// As [`TensorFile::read_bytes`]; [`Error::File`] when the field is not uint16.
    pub fn read_u16_all(&mut self, name: &str) -> Result<Vec<u16>> {
        self.expect_dtype(name, Dtype::U16)?;
        let n = self.field(name)?.len() as usize;
        let mut b = vec![0u8; n * 2];
        self.read_bytes(name, 0, &mut b)?;
        Ok(b.chunks_exact(2)
            .map(|c| u16::from_le_bytes(c.try_into().expect("2 bytes")))
            .collect())
    }

    /// Checks a field's dtype.
    ///
    /// # Errors
    /// [`Error::File`] naming the field, the expected and the found dtype.
    pub fn expect_dtype(&self, name: &str, dtype: Dtype) -> Result<()> {
        let f = self.field(name)?;
        if f.dtype != dtype {
            return Err(field_err(
                &self.path,
                name,
                format!(
                    "dtype {} where {} is required",
                    f.dtype.name(),
                    dtype.name()
                ),
            ));
        }
        Ok(())
    }
}

/// A producer of a field's bytes.
pub type Producer<'a> = Box<dyn FnMut(&mut dyn Write) -> std::io::Result<()> + 'a>;

/// A field to write: its header and a producer of its bytes.
pub struct FieldData<'a> {
    /// Name.
    pub name: &'a str,
    /// Element type.
    pub dtype: Dtype,
    /// Shape.
    pub shape: Vec<u64>,
    /// Writes exactly `shape × dtype size` bytes into the writer.
    pub write: Producer<'a>,
}

/// Writes a TensorFile through the output layer ([`crate::Output`]: a regular file atomically,
/// a device or FIFO directly, `-` to standard output; a read-only or hard-linked file is refused),
/// streaming each field's data in order (no seek). Data offsets are aligned to 8.
///
/// # Errors
/// As [`crate::Output::create`]; [`Error::Write`] naming `path`. On error nothing changes at a
/// regular `path`.
pub fn write_tensor_file(path: &Path, fields: Vec<FieldData<'_>>) -> Result<()> {
    let mut header_len: u64 = 12 + 2 + 4;
    for f in &fields {
        header_len += 2 + f.name.len() as u64 + 2 + 1 + 8 + 8 * f.shape.len() as u64;
    }
    let align = |x: u64| x.div_ceil(8) * 8;
    let mut offsets = Vec::new();
    let mut at = align(header_len);
    for f in &fields {
        offsets.push(at);
        at = align(at + f.shape.iter().product::<u64>() * f.dtype.size());
    }
    let mut out = crate::write::Output::create(path)?;
    let written = write_fields(&mut out, fields, &offsets);
    written.map_err(|e| out.error(e))?;
    out.commit()
}

/// The header and the data of `fields` (at `offsets`) into `w`.
fn write_fields(
    w: &mut dyn Write,
    fields: Vec<FieldData<'_>>,
    offsets: &[u64],
) -> std::io::Result<()> {
    let mut head: Vec<u8> = Vec::new();
    head.extend_from_slice(MAGIC);
    head.extend_from_slice(&[1, 0]);
    head.extend_from_slice(&(fields.len() as u32).to_le_bytes());
    for (f, off) in fields.iter().zip(offsets) {
        head.extend_from_slice(&(f.name.len() as u16).to_le_bytes());
        head.extend_from_slice(f.name.as_bytes());
        head.extend_from_slice(&(f.shape.len() as u16).to_le_bytes());
        head.push(f.dtype.code());
        head.extend_from_slice(&off.to_le_bytes());
        for d in &f.shape {
            head.extend_from_slice(&d.to_le_bytes());
        }
    }
    w.write_all(&head)?;
    let mut pos = head.len() as u64;
    for (mut f, &off) in fields.into_iter().zip(offsets) {
        w.write_all(&vec![0u8; (off - pos) as usize])?;
        let expected = f.shape.iter().product::<u64>() * f.dtype.size();
        let mut counter = Counting { inner: w, n: 0 };
        (f.write)(&mut counter)?;
        if counter.n != expected {
            return Err(std::io::Error::other(format!(
                "field `{}`: {} bytes produced, {} expected",
                f.name, counter.n, expected
            )));
        }
        pos = off + expected;
    }
    Ok(())
}

struct Counting<'a, W: Write + ?Sized> {
    inner: &'a mut W,
    n: u64,
}

impl<W: Write + ?Sized> Write for Counting<'_, W> {
    fn write(&mut self, b: &[u8]) -> std::io::Result<usize> {
        let k = self.inner.write(b)?;
        self.n += k as u64;
        Ok(k)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.inner.flush()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn written_files_read_back_and_mitsubas_layout_holds() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.pbsdf");
        let a: Vec<u8> = [1.5f32, -2.0, 3.25]
            .iter()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        let b: Vec<u8> = [7u16, 9].iter().flat_map(|x| x.to_le_bytes()).collect();
        let fields = vec![
            FieldData {
                name: "abc",
                dtype: Dtype::F32,
                shape: vec![1, 3],
                write: Box::new(move |w: &mut dyn Write| w.write_all(&a)),
            },
            FieldData {
                name: "w",
                dtype: Dtype::U16,
                shape: vec![2],
                write: Box::new(move |w: &mut dyn Write| w.write_all(&b)),
            },
        ];
        write_tensor_file(&path, fields).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        assert_eq!(&bytes[..12], MAGIC);
        assert_eq!(&bytes[12..14], &[1, 0]);
        assert_eq!(u32::from_le_bytes(bytes[14..18].try_into().unwrap()), 2);
        let mut t = TensorFile::open(&path).unwrap();
        let f = t.field("abc").unwrap().clone();
        assert_eq!(
            (f.dtype, f.shape.clone(), f.offset % 8),
            (Dtype::F32, vec![1, 3], 0)
        );
        assert_eq!(t.read_f32("abc", 0, 3).unwrap(), vec![1.5, -2.0, 3.25]);
        assert_eq!(t.read_u16_all("w").unwrap(), vec![7, 9]);
        assert!(t
            .read_f32("w", 0, 1)
            .unwrap_err()
            .to_string()
            .contains("dtype uint16 where float32"));
        assert!(t.read_f32("abc", 2, 2).is_err());
    }

    #[test]
    fn a_producer_of_the_wrong_length_leaves_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.pbsdf");
        let fields = vec![FieldData {
            name: "x",
            dtype: Dtype::F64,
            shape: vec![2],
            write: Box::new(|w: &mut dyn Write| w.write_all(&[0u8; 8])),
        }];
        let e = write_tensor_file(&path, fields).unwrap_err().to_string();
        assert!(e.contains("8 bytes produced, 16 expected"), "{e}");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    }
}
