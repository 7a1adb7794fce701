//! The geometry table (`polbrdf eval`'s input, whole or in chunks) and the checks of a row's
//! geometry and wavelength that every table reader shares (CSV, `.npy`, Arrow, measurements).

use super::fields::parse_number;
use super::message::show;
use super::reader::{CsvReader, Record};
use crate::error::{Error, Result};
use polbrdf::Geometry;
use std::io::BufRead;
use std::path::{Path, PathBuf};

/// The four angle columns every geometry file must have (degrees, any order).
pub const ANGLE_COLUMNS: [&str; 4] = ["theta_i_deg", "phi_i_deg", "theta_r_deg", "phi_r_deg"];

/// The columns `polbrdf eval` reads instead of [`ANGLE_COLUMNS`]: the direction vectors `w_i`
/// (toward the source) and `w_r` (toward the detector) in the surface frame, z along the
/// normal, of any length within `polbrdf::geometry::angles::DIRECTION_LENGTH` (docs/model.md
/// §9.11; the core's `DirectionBatch`).
pub const DIRECTION_COLUMNS: [&str; 6] = ["w_i_x", "w_i_y", "w_i_z", "w_r_x", "w_r_y", "w_r_z"];

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
    let wl = reader.headers().iter().position(|h| h == WAVELENGTH_COLUMN);
    let path = reader.path().to_path_buf();
    let headers = reader.headers().to_vec();
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
