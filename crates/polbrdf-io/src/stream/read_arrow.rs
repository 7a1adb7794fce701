//! The Arrow chunk reader: a chunk's columns as the table gives them, the geometry and
//! wavelength columns required to be numbers and each row checked as a CSV row's is.

use super::chunk::{Geometries, GeometryChunk, Passthrough};
use super::columns::{Layout, RowGeometries};
use crate::arrow::ArrowReader;
use crate::csv_io::check_wavelength;
use crate::error::{Error, Result};
use crate::table::Column;

/// The next at most `max` rows of an Arrow table as a chunk, or `None` at its end: the
/// geometry columns checked to be numbers, then each row's geometry, then the wavelength
/// column and each row's wavelength.
pub(super) fn arrow_chunk(
    reader: &mut ArrowReader,
    layout: &Layout<'_>,
    max: usize,
) -> Result<Option<GeometryChunk>> {
    let first = reader.rows_read() as usize + 1;
    let Some(cols) = reader.next_rows(max)? else {
        return Ok(None);
    };
    let n = match cols.first() {
        Some(Column::Numbers(v)) => v.len(),
        Some(Column::Text(v)) => v.len(),
        None => 0,
    };
    let lines: Vec<usize> = (first..first + n).collect();
    let geometries = geometries(layout, &cols, &lines, first)?;
    let wavelengths = match layout.wavelength {
        Some(w) => Some(
            numbers(layout, &cols, w, first)?
                .iter()
                .zip(&lines)
                .map(|(&v, &line)| check_wavelength(layout.path, line, v))
                .collect::<Result<Vec<f64>>>()?,
        ),
        None => None,
    };
    Ok(Some(GeometryChunk {
        lines,
        geometries,
        wavelengths,
        columns: Passthrough::Columns(cols),
    }))
}

/// The numbers of column `i` of a chunk whose first row is `first`: an error naming the column
/// for a text column (the angle and wavelength columns must be numbers).
fn numbers<'c>(
    layout: &Layout<'_>,
    cols: &'c [Column],
    i: usize,
    first: usize,
) -> Result<&'c [f64]> {
    match &cols[i] {
        Column::Numbers(v) => Ok(v),
        Column::Text(v) => Err(Error::Field {
            path: layout.path.to_path_buf(),
            line: first,
            field: layout.headers[i].clone(),
            message: format!(
                "a text column (`{}`); this column must hold numbers",
                v.first().map(String::as_str).unwrap_or("")
            ),
        }),
    }
}

/// The geometries of a chunk's rows (at `lines`, the first row being `first`) from its
/// geometry columns, each of which must hold numbers.
fn geometries(
    layout: &Layout<'_>,
    cols: &[Column],
    lines: &[usize],
    first: usize,
) -> Result<Geometries> {
    // The geometry columns' numbers, by column index (the others left empty).
    let mut by_column: Vec<&[f64]> = vec![&[]; cols.len()];
    for &i in layout.geometry.indices() {
        by_column[i] = numbers(layout, cols, i, first)?;
    }
    let mut rows = RowGeometries::new(layout.geometry, lines.len());
    for (k, &line) in lines.iter().enumerate() {
        rows.push(layout.path, line, |i| by_column[i][k])?;
    }
    Ok(rows.finish())
}
