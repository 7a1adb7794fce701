//! The CSV chunk reader: a chunk's records kept as text, their geometries parsed in parallel.

use super::chunk::{
    Geometries, GeometryChunk, Passthrough, TextRows, CHUNK_ROWS, CHUNK_TEXT_BYTES,
};
use super::columns::{GeometryColumns, Layout};
use crate::csv_io::{row_directions, row_geometry, row_wavelength, CsvReader};
use crate::error::Result;
use polbrdf::Geometry;
use std::io::BufRead;
use std::path::Path;

/// The next at most `max` rows of a CSV table as a chunk (no rows at the end of the file): the
/// records, then their geometries, then their wavelengths. Errors come in that order; within
/// each step the first bad row in file order is the error.
pub(super) fn csv_chunk<R: BufRead>(
    reader: &mut CsvReader<R>,
    layout: &Layout<'_>,
    max: usize,
) -> Result<GeometryChunk> {
    let (records, lines) = read_records(reader, layout.headers.len(), max)?;
    let geometries = parse_geometries(layout.path, layout.geometry, &records, &lines)?;
    let wavelengths = match layout.wavelength {
        Some(w) => Some(parse_wavelengths(layout.path, w, &records, &lines)?),
        None => None,
    };
    Ok(GeometryChunk {
        lines,
        geometries,
        wavelengths,
        columns: Passthrough::Text(records),
    })
}

/// The next records of `reader` (`width` fields each) and their lines: at most `max` rows, and
/// no more once [`CHUNK_TEXT_BYTES`] of field text are held.
fn read_records<R: BufRead>(
    reader: &mut CsvReader<R>,
    width: usize,
    max: usize,
) -> Result<(TextRows, Vec<usize>)> {
    let cap = max.min(CHUNK_ROWS);
    let mut records = TextRows::with_capacity(cap, width);
    let mut lines = Vec::with_capacity(cap);
    while lines.len() < max && records.text_len() < CHUNK_TEXT_BYTES {
        let Some(r) = reader.next_record()? else {
            break;
        };
        lines.push(r.line);
        records.push(&r);
    }
    Ok((records, lines))
}

/// The geometries of the records from their geometry columns, parsed in parallel; the first
/// bad row (in file order) is the error.
fn parse_geometries(
    path: &Path,
    columns: GeometryColumns,
    records: &TextRows,
    lines: &[usize],
) -> Result<Geometries> {
    use rayon::prelude::*;
    Ok(match columns {
        GeometryColumns::Angles(idx) => {
            let parsed: Vec<Result<Geometry>> = lines
                .par_iter()
                .enumerate()
                .map(|(k, &line)| row_geometry(path, line, idx.map(|i| records.field(k, i))))
                .collect();
            Geometries::Angles(parsed.into_iter().collect::<Result<_>>()?)
        }
        GeometryColumns::Directions(idx) => {
            let parsed: Vec<Result<([f64; 3], [f64; 3])>> = lines
                .par_iter()
                .enumerate()
                .map(|(k, &line)| row_directions(path, line, idx.map(|i| records.field(k, i))))
                .collect();
            let pairs = parsed.into_iter().collect::<Result<Vec<_>>>()?;
            let (w_i, w_r) = pairs.into_iter().unzip();
            Geometries::Directions { w_i, w_r }
        }
    })
}

/// The wavelengths of the records from column `w` (µm, finite and > 0).
fn parse_wavelengths(
    path: &Path,
    w: usize,
    records: &TextRows,
    lines: &[usize],
) -> Result<Vec<f64>> {
    lines
        .iter()
        .enumerate()
        .map(|(k, &line)| row_wavelength(path, line, records.field(k, w)))
        .collect()
}
