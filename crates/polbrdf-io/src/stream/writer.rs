//! The result table of `eval` written chunk by chunk: one sink per output format, committed at
//! the end.

use super::chunk::GeometryChunk;
#[cfg(feature = "arrow")]
use super::encode::{arrow_columns, chunk_kinds};
use super::encode::{csv_row, fill_npy_rows};
#[cfg(not(feature = "arrow"))]
use super::format::no_arrow;
use super::format::Format;
use crate::csv_io::result_columns;
use crate::error::{Error, Result};
use crate::npy::NpyWriter;
use crate::table::{Kind, RowResult};
use crate::write::Output;
use std::io::{Seek, Write};
use std::path::{Path, PathBuf};

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
