//! Arrow IPC tables (feature `arrow`): the IPC **file** format (`.arrow`, `.feather` — Feather
//! v2 is the IPC file format) and the IPC **stream** format (`.arrows`), read record batch by
//! record batch and written one record batch per chunk, so memory stays bounded.
//!
//! Input columns may be Float64, Float32 or any integer type (read as f64), or text (Utf8,
//! LargeUtf8, Utf8View: passed through as text). A null is an error naming its 1-based row
//! and column. Output columns are Float64, except text passed through, which stays text.

use crate::error::{Error, Result};
pub use crate::table::{Column, Kind};
use arrow_array::cast::AsArray;
use arrow_array::types::{
    Float32Type, Float64Type, Int16Type, Int32Type, Int64Type, Int8Type, UInt16Type, UInt32Type,
    UInt64Type, UInt8Type,
};
use arrow_array::{Array, ArrayRef, Float64Array, RecordBatch, StringArray};
use arrow_schema::{ArrowError, DataType, Field, Schema, SchemaRef};
use std::io::{BufReader, Read, Seek, Write};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// An Arrow error as the crate's error, naming the file and `what` (e.g. "batch 3").
pub fn arrow_err(path: &Path, what: &str, e: ArrowError) -> Error {
    match e {
        // Reading past the end or seeking before the start: the offsets of a truncated or
        // malformed file.
        ArrowError::IoError(_, source)
            if matches!(
                source.kind(),
                std::io::ErrorKind::UnexpectedEof
                    | std::io::ErrorKind::InvalidInput
                    | std::io::ErrorKind::InvalidData
            ) =>
        {
            Error::File {
                path: path.to_path_buf(),
                message: format!("Arrow IPC {what}: the file is truncated or malformed ({source})"),
            }
        }
        ArrowError::IoError(_, source) => Error::Read {
            path: path.to_path_buf(),
            source,
        },
        // Compressed batches (pandas' `to_feather` compresses with LZ4 by default) are not
        // decoded: arrow-ipc's decoders reserve the uncompressed size a buffer claims before
        // reading it (an abort for a lying claim), and its ZSTD links a C library.
        ArrowError::InvalidArgumentError(m)
            if m.starts_with("lz4 IPC decompression")
                || m.starts_with("zstd IPC decompression") =>
        {
            Error::File {
                path: path.to_path_buf(),
                message: format!(
                    "Arrow IPC {what}: compressed ({}), which polbrdf does not read; save the \
                     table uncompressed — pandas: `df.to_feather(path, \
                     compression=\"uncompressed\")`; pyarrow: \
                     `pyarrow.feather.write_feather(table, path, compression=\"uncompressed\")`",
                    if m.starts_with("lz4") { "LZ4" } else { "ZSTD" }
                ),
            }
        }
        other => Error::File {
            path: path.to_path_buf(),
            message: format!("Arrow IPC {what}: {other}"),
        },
    }
}

thread_local! {
    /// True while this thread runs Arrow's decoder under [`guarded`].
    static QUIET: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Runs `f` (a call into Arrow's decoder) so that a panic on malformed input becomes an
/// [`Error::File`] naming `path` and `what`, printed by no panic hook.
fn guarded<T>(
    path: &Path,
    what: &str,
    f: impl FnOnce() -> std::result::Result<T, ArrowError>,
) -> Result<T> {
    static HOOK: std::sync::Once = std::sync::Once::new();
    HOOK.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !QUIET.with(|q| q.get()) {
                previous(info);
            }
        }));
    });
    QUIET.with(|q| q.set(true));
    let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(f));
    QUIET.with(|q| q.set(false));
    match r {
        Ok(r) => r.map_err(|e| arrow_err(path, what, e)),
        Err(_) => Err(Error::File {
            path: path.to_path_buf(),
            message: format!("Arrow IPC {what}: malformed (the decoder rejected it)"),
        }),
    }
}

/// Checks an IPC file's footer before Arrow reads it: every block it lists (dictionaries,
/// record batches) lies inside the file, so that no block makes the decoder allocate more than
/// the file holds (a corrupted length would otherwise be allocated before the read fails).
/// Leaves `src` at its start. A file too short for a footer, or without the trailing magic, is
/// left to the decoder's own error.
fn check_blocks<R: Read + Seek>(src: &mut R, path: &Path) -> Result<()> {
    use std::io::SeekFrom;
    let io = |source| Error::Read {
        path: path.to_path_buf(),
        source,
    };
    let bad = |message: String| Error::File {
        path: path.to_path_buf(),
        message: format!("Arrow IPC file: {message}"),
    };
    let len = src.seek(SeekFrom::End(0)).map_err(io)?;
    if len >= 18 {
        let mut tail = [0u8; 10];
        src.seek(SeekFrom::End(-10)).map_err(io)?;
        src.read_exact(&mut tail).map_err(io)?;
        if &tail[4..] == b"ARROW1" {
            let footer_len = i64::from(i32::from_le_bytes([tail[0], tail[1], tail[2], tail[3]]));
            if footer_len < 0 || footer_len as u64 + 10 > len {
                return Err(bad(format!(
                    "footer length {footer_len} does not fit in a file of {len} bytes"
                )));
            }
            let end = len - 10 - footer_len as u64;
            let mut footer = vec![0u8; footer_len as usize];
            src.seek(SeekFrom::Start(end)).map_err(io)?;
            src.read_exact(&mut footer).map_err(io)?;
            let f = arrow_ipc::root_as_footer(&footer)
                .map_err(|e| bad(format!("malformed footer ({e})")))?;
            let blocks = f
                .dictionaries()
                .into_iter()
                .chain(f.recordBatches())
                .flatten();
            for (i, b) in blocks.enumerate() {
                let fits = b.offset() >= 0
                    && b.metaDataLength() >= 0
                    && b.bodyLength() >= 0
                    && (b.offset() as u64)
                        .checked_add(b.metaDataLength() as u64)
                        .and_then(|x| x.checked_add(b.bodyLength() as u64))
                        .is_some_and(|x| x <= end);
                if !fits {
                    return Err(bad(format!(
                        "block {} (offset {}, {} + {} bytes) lies outside the file's {end} bytes \
                         of data",
                        i + 1,
                        b.offset(),
                        b.metaDataLength(),
                        b.bodyLength()
                    )));
                }
            }
        }
    }
    src.seek(SeekFrom::Start(0)).map_err(io)?;
    Ok(())
}

/// The kind of a column of Arrow type `t`, or `None` for a type `eval` cannot read.
fn kind_of(t: &DataType) -> Option<Kind> {
    use DataType as D;
    match t {
        D::Float64
        | D::Float32
        | D::Int8
        | D::Int16
        | D::Int32
        | D::Int64
        | D::UInt8
        | D::UInt16
        | D::UInt32
        | D::UInt64 => Some(Kind::Number),
        D::Utf8 | D::LargeUtf8 | D::Utf8View => Some(Kind::Text),
        _ => None,
    }
}

type Batches = Box<dyn Iterator<Item = std::result::Result<RecordBatch, ArrowError>> + Send>;

/// A streaming reader of an Arrow IPC table: the schema, then rows in chunks.
pub struct ArrowReader {
    path: PathBuf,
    columns: Vec<String>,
    kinds: Vec<Kind>,
    batches: Batches,
    /// The batch being read, and the next row in it.
    current: Option<(RecordBatch, usize)>,
    /// Batches read so far.
    batch_index: usize,
    rows_read: u64,
    rows_hint: Option<u64>,
}

impl std::fmt::Debug for ArrowReader {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ArrowReader")
            .field("path", &self.path)
            .field("columns", &self.columns)
            .finish_non_exhaustive()
    }
}

impl ArrowReader {
    /// Opens an IPC file (footer and random access; `src` must seek).
    ///
    /// # Errors
    /// [`Error::File`] naming `path` for a file that is not Arrow IPC, a malformed schema or a
    /// column of a type that cannot be read; [`Error::Read`].
    pub fn file<R: Read + Seek + Send + 'static>(mut src: R, path: &Path) -> Result<Self> {
        check_blocks(&mut src, path)?;
        let r = guarded(path, "file", || {
            arrow_ipc::reader::FileReader::try_new_buffered(src, None)
        })?;
        let schema = r.schema();
        Self::new(path, schema, Box::new(r), None)
    }

    /// Opens an IPC file front to back, as the stream it holds after its 8-byte magic (for a
    /// source that cannot seek; the footer is not read).
    ///
    /// # Errors
    /// As [`file`](Self::file).
    pub fn file_sequential<R: Read + Send + 'static>(mut src: R, path: &Path) -> Result<Self> {
        let mut magic = [0u8; 8];
        src.read_exact(&mut magic).map_err(|e| {
            if e.kind() == std::io::ErrorKind::UnexpectedEof {
                Error::File {
                    path: path.to_path_buf(),
                    message: "not an Arrow IPC file (shorter than its magic ARROW1)".into(),
                }
            } else {
                Error::Read {
                    path: path.to_path_buf(),
                    source: e,
                }
            }
        })?;
        if &magic[..6] != b"ARROW1" {
            return Err(Error::File {
                path: path.to_path_buf(),
                message: "not an Arrow IPC file (it does not start with ARROW1)".into(),
            });
        }
        Self::stream(src, path)
    }

    /// Opens an IPC stream (read front to back; `src` need not seek).
    ///
    /// # Errors
    /// As [`file`](Self::file).
    pub fn stream<R: Read + Send + 'static>(src: R, path: &Path) -> Result<Self> {
        let r = guarded(path, "stream", || {
            arrow_ipc::reader::StreamReader::try_new(BufReader::with_capacity(1 << 16, src), None)
        })?;
        let schema = r.schema();
        Self::new(path, schema, Box::new(r), None)
    }

    fn new(
        path: &Path,
        schema: SchemaRef,
        batches: Batches,
        rows_hint: Option<u64>,
    ) -> Result<Self> {
        // A batch without columns can claim any number of rows at no cost in bytes (found by
        // the fuzz target: 2⁴⁰ rows of nothing, read 7 at a time); no table of `eval` has none.
        if schema.fields().is_empty() {
            return Err(Error::File {
                path: path.to_path_buf(),
                message: "an Arrow table without columns".into(),
            });
        }
        let mut columns = Vec::with_capacity(schema.fields().len());
        let mut kinds = Vec::with_capacity(schema.fields().len());
        for f in schema.fields() {
            let Some(k) = kind_of(f.data_type()) else {
                return Err(Error::File {
                    path: path.to_path_buf(),
                    message: format!(
                        "Arrow column `{}` has type {}; supported are floats, integers and text",
                        f.name(),
                        f.data_type()
                    ),
                });
            };
            if f.name().is_empty() {
                return Err(Error::File {
                    path: path.to_path_buf(),
                    message: "an Arrow column has an empty name".into(),
                });
            }
            if columns.contains(f.name()) {
                return Err(Error::File {
                    path: path.to_path_buf(),
                    message: format!("Arrow column `{}` appears twice", f.name()),
                });
            }
            columns.push(f.name().clone());
            kinds.push(k);
        }
        Ok(Self {
            path: path.to_path_buf(),
            columns,
            kinds,
            batches,
            current: None,
            batch_index: 0,
            rows_read: 0,
            rows_hint,
        })
    }

    /// The column names.
    pub fn columns(&self) -> &[String] {
        &self.columns
    }

    /// Each column's kind.
    pub fn kinds(&self) -> &[Kind] {
        &self.kinds
    }

    /// The number of rows when known in advance.
    pub fn rows_hint(&self) -> Option<u64> {
        self.rows_hint
    }

    /// Rows read so far.
    pub fn rows_read(&self) -> u64 {
        self.rows_read
    }

    /// Up to `max` rows (fewer at a batch's end), column by column, or `None` at the end.
    ///
    /// # Errors
    /// [`Error::File`] naming the batch for a corrupted or truncated file, a batch whose
    /// schema differs; [`Error::Field`] naming the row and column of a null; [`Error::Read`].
    pub fn next_rows(&mut self, max: usize) -> Result<Option<Vec<Column>>> {
        loop {
            if let Some((batch, at)) = &self.current {
                if *at < batch.num_rows() {
                    break;
                }
            }
            self.current = None;
            let what = format!("batch {}", self.batch_index + 1);
            let batches = &mut self.batches;
            let Some(batch) = guarded(&self.path, &what, || batches.next().transpose())? else {
                return Ok(None);
            };
            self.batch_index += 1;
            if batch.num_columns() != self.columns.len()
                || batch
                    .schema()
                    .fields()
                    .iter()
                    .zip(&self.kinds)
                    .any(|(f, k)| kind_of(f.data_type()) != Some(*k))
            {
                return Err(Error::File {
                    path: self.path.clone(),
                    message: format!("Arrow IPC {what}: its columns differ from the schema's"),
                });
            }
            self.current = Some((batch, 0));
        }
        let (batch, at) = self.current.as_mut().expect("a batch");
        let start = *at;
        let n = max.min(batch.num_rows() - start).max(1);
        *at += n;
        let first = self.rows_read + 1;
        self.rows_read += n as u64;
        let mut out = Vec::with_capacity(self.columns.len());
        for (i, name) in self.columns.iter().enumerate() {
            let col = batch.column(i).slice(start, n);
            if col.null_count() > 0 {
                let k = (0..n).find(|&k| col.is_null(k)).unwrap_or(0);
                return Err(Error::Field {
                    path: self.path.clone(),
                    line: (first + k as u64) as usize,
                    field: name.clone(),
                    message: "null value (a table for eval has no nulls)".into(),
                });
            }
            out.push(column_of(&col));
        }
        Ok(Some(out))
    }
}

/// The values of an array of a readable type (checked by [`kind_of`]).
fn column_of(a: &ArrayRef) -> Column {
    macro_rules! nums {
        ($t:ty) => {
            Column::Numbers(
                a.as_primitive::<$t>()
                    .values()
                    .iter()
                    .map(|&x| x as f64)
                    .collect(),
            )
        };
    }
    match a.data_type() {
        DataType::Float64 => Column::Numbers(a.as_primitive::<Float64Type>().values().to_vec()),
        DataType::Float32 => nums!(Float32Type),
        DataType::Int8 => nums!(Int8Type),
        DataType::Int16 => nums!(Int16Type),
        DataType::Int32 => nums!(Int32Type),
        DataType::Int64 => nums!(Int64Type),
        DataType::UInt8 => nums!(UInt8Type),
        DataType::UInt16 => nums!(UInt16Type),
        DataType::UInt32 => nums!(UInt32Type),
        DataType::UInt64 => nums!(UInt64Type),
        DataType::Utf8 => Column::Text(
            a.as_string::<i32>()
                .iter()
                .map(|s| s.unwrap_or("").to_string())
                .collect(),
        ),
        DataType::LargeUtf8 => Column::Text(
            a.as_string::<i64>()
                .iter()
                .map(|s| s.unwrap_or("").to_string())
                .collect(),
        ),
        DataType::Utf8View => Column::Text(
            a.as_string_view()
                .iter()
                .map(|s| s.unwrap_or("").to_string())
                .collect(),
        ),
        other => unreachable!("type {other} is refused when the schema is read"),
    }
}

enum Writer<W: Write> {
    File(arrow_ipc::writer::FileWriter<W>),
    Stream(arrow_ipc::writer::StreamWriter<W>),
}

/// A streaming writer of an Arrow IPC table (file or stream format): one record batch per
/// call of [`write_batch`](Self::write_batch).
pub struct ArrowWriter<W: Write> {
    w: Writer<W>,
    schema: SchemaRef,
}

impl<W: Write> std::fmt::Debug for ArrowWriter<W> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ArrowWriter")
            .field("schema", &self.schema)
            .finish_non_exhaustive()
    }
}

impl<W: Write> ArrowWriter<W> {
    /// Starts a table of the columns `columns` (each with its kind: Float64 or Utf8, not
    /// nullable) in `w`; `stream` picks the stream format, else the file format.
    ///
    /// # Errors
    /// The Arrow error of writing the schema.
    pub fn new(
        w: W,
        columns: &[(String, Kind)],
        stream: bool,
    ) -> std::result::Result<Self, ArrowError> {
        let fields: Vec<Field> = columns
            .iter()
            .map(|(name, k)| {
                let t = match k {
                    Kind::Number => DataType::Float64,
                    Kind::Text => DataType::Utf8,
                };
                Field::new(name, t, false)
            })
            .collect();
        let schema = Arc::new(Schema::new(fields));
        let w = if stream {
            Writer::Stream(arrow_ipc::writer::StreamWriter::try_new(w, &schema)?)
        } else {
            Writer::File(arrow_ipc::writer::FileWriter::try_new(w, &schema)?)
        };
        Ok(Self { w, schema })
    }

    /// Writes one record batch of `columns` (as many as the schema, of its kinds, of equal
    /// length).
    ///
    /// # Errors
    /// The Arrow error of building or writing the batch.
    pub fn write_batch(&mut self, columns: Vec<Column>) -> std::result::Result<(), ArrowError> {
        let arrays: Vec<ArrayRef> = columns
            .into_iter()
            .map(|c| -> ArrayRef {
                match c {
                    Column::Numbers(v) => Arc::new(Float64Array::from(v)),
                    Column::Text(v) => Arc::new(StringArray::from(v)),
                }
            })
            .collect();
        let batch = RecordBatch::try_new(self.schema.clone(), arrays)?;
        match &mut self.w {
            Writer::File(w) => w.write(&batch),
            Writer::Stream(w) => w.write(&batch),
        }
    }

    /// Writes the end (the stream's end marker; the file's footer) and returns the sink.
    ///
    /// # Errors
    /// The Arrow error of writing the end.
    pub fn finish(self) -> std::result::Result<W, ArrowError> {
        match self.w {
            Writer::File(mut w) => {
                w.finish()?;
                w.into_inner()
            }
            Writer::Stream(mut w) => {
                w.finish()?;
                w.into_inner()
            }
        }
    }
}

/// An Arrow writer's error as the crate's error for the output `path`.
pub fn write_err(path: &Path, e: ArrowError) -> Error {
    match e {
        ArrowError::IoError(_, source) => Error::Write {
            path: path.to_path_buf(),
            source,
        },
        other => Error::File {
            path: path.to_path_buf(),
            message: format!("cannot write an Arrow table: {other}"),
        },
    }
}
