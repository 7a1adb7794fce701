//! A chunk's rows with their results encoded for each output format: CSV text, `.npy` numbers,
//! Arrow columns.

#[cfg(feature = "arrow")]
use super::chunk::CHUNK_ROWS;
use super::chunk::{GeometryChunk, Passthrough};
use crate::csv_io::{fmt_f64_into, parse_number};
use crate::error::{Error, Result};
#[cfg(feature = "arrow")]
use crate::table::Kind;
use crate::table::{result_values, Column, RowResult};
use std::path::Path;

/// The kinds of a chunk's input columns for an Arrow output: `.npy` and Arrow input say them;
/// a CSV column is numbers when every field of the first chunk is a number, else text.
#[cfg(feature = "arrow")]
pub(super) fn chunk_kinds(
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
pub(super) fn arrow_columns(
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
    parse_number(input, line, name, text).map_err(|e| e.with_more(&format!(" ({why})")))
}

/// One CSV row of the result table: row `k`'s input columns, then its 19 result values.
pub(super) fn csv_row(
    line: &mut Vec<u8>,
    columns: &Passthrough,
    k: usize,
    cols: usize,
    f: &RowResult,
) {
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
pub(super) fn fill_npy_rows(
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
