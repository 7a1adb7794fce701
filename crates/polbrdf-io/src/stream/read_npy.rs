//! The `.npy` chunk reader: a chunk's rows read as numbers, each row's geometry and wavelength
//! checked as a CSV row's are.

use super::chunk::{GeometryChunk, Passthrough};
use super::columns::{Layout, RowGeometries};
use crate::csv_io::check_wavelength;
use crate::error::Result;
use crate::npy::NpyReader;
use std::io::Read;

/// The next at most `max` rows of a `.npy` table as a chunk (no rows at the end of the file),
/// its numbers read into `buf` (whose storage the chunk takes). Each row's geometry, then its
/// wavelength, is checked before the next row's.
pub(super) fn npy_chunk<R: Read>(
    reader: &mut NpyReader<R>,
    layout: &Layout<'_>,
    max: usize,
    buf: &mut Vec<f64>,
) -> Result<GeometryChunk> {
    let first = reader.rows_read() as usize + 1;
    let n = read_numbers(reader, max, buf)?;
    let lines: Vec<usize> = (first..first + n).collect();
    let mut rows = RowGeometries::new(layout.geometry, n);
    let mut wavelengths = layout.wavelength.map(|_| Vec::with_capacity(n));
    for (row, &line) in buf.chunks_exact(layout.headers.len()).zip(&lines) {
        rows.push(layout.path, line, |i| row[i])?;
        if let (Some(w), Some(out)) = (layout.wavelength, wavelengths.as_mut()) {
            out.push(check_wavelength(layout.path, line, row[w])?);
        }
    }
    Ok(GeometryChunk {
        lines,
        geometries: rows.finish(),
        wavelengths,
        columns: Passthrough::Numbers(std::mem::take(buf)),
    })
}

/// Reads up to `max` rows into `buf` (cleared first), row-major; returns the rows read (fewer
/// only at the end of the file).
fn read_numbers<R: Read>(
    reader: &mut NpyReader<R>,
    max: usize,
    buf: &mut Vec<f64>,
) -> Result<usize> {
    buf.clear();
    let mut n = 0;
    while n < max {
        let k = reader.read_rows(max - n, buf)?;
        if k == 0 {
            break;
        }
        n += k;
    }
    Ok(n)
}
