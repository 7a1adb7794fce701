//! The CSV tables of detection (docs/detection.md): a path table (`range_m, transmittance,
//! path_radiance`, the format a MODTRAN or libRadtran user exports) and a quantum-efficiency
//! table (`wavelength_um, qe`).

use crate::csv_io::{parse_number, row_error, CsvReader};
use crate::error::{Error, Result};
use polbrdf::analysis::detection::path::MAX_PATH_ROWS;
use polbrdf::analysis::detection::{Path as AirPath, QuantumEfficiency};
use std::io::BufRead;
use std::path::Path;

/// The columns of a path table: range (m), transmittance (in [0, 1]) and the path's spectral
/// radiance (W·m⁻²·sr⁻¹·µm⁻¹, taken as constant across the sensor's band).
pub const PATH_COLUMNS: [&str; 3] = ["range_m", "transmittance", "path_radiance"];

/// The columns of a quantum-efficiency table: wavelength (µm) and QE (in [0, 1]).
pub const QE_COLUMNS: [&str; 2] = ["wavelength_um", "qe"];

/// The most rows of a QE table.
pub const MAX_QE_ROWS: usize = 10_000;

/// Reads the numeric `columns` of every row, at most `max` rows (the row past it an error
/// naming its line): the rows and their lines.
fn rows<R: BufRead, const N: usize>(
    mut reader: CsvReader<R>,
    columns: &[&str; N],
    max: usize,
) -> Result<(Vec<[f64; N]>, Vec<usize>)> {
    let index = reader.require(columns)?;
    let path = reader.path().to_path_buf();
    let (mut rows, mut lines) = (Vec::new(), Vec::new());
    while let Some(r) = reader.next_record()? {
        if rows.len() == max {
            return Err(Error::Field {
                path,
                line: r.line,
                field: columns[0].to_string(),
                message: format!("a table has at most {max} rows"),
            });
        }
        let mut row = [0.0; N];
        for (k, v) in row.iter_mut().enumerate() {
            *v = parse_number(&path, r.line, columns[k], r.get(index[k]))?;
        }
        rows.push(row);
        lines.push(r.line);
    }
    Ok((rows, lines))
}

/// Reads a path table ([`PATH_COLUMNS`] in any order, other columns ignored; ranges strictly
/// increasing, never extrapolated beyond the last row).
///
/// # Errors
/// [`Error::Field`] naming the file, the line and the column for a malformed or invalid value;
/// [`Error::File`] for a missing column or no row.
pub fn read_path_csv(path: &Path) -> Result<AirPath> {
    path_from(CsvReader::open(path)?)
}

/// Parses path-table CSV bytes ([`read_path_csv`]); `path` names it in messages.
///
/// # Errors
/// As [`read_path_csv`].
pub fn parse_path_csv(bytes: &[u8], path: &Path) -> Result<AirPath> {
    path_from(CsvReader::new(bytes, path)?)
}

fn path_from<R: BufRead>(reader: CsvReader<R>) -> Result<AirPath> {
    let path = reader.path().to_path_buf();
    let (rows, lines) = rows(reader, &PATH_COLUMNS, MAX_PATH_ROWS)?;
    let rows: Vec<(f64, f64, f64)> = rows.iter().map(|r| (r[0], r[1], r[2])).collect();
    AirPath::table(&rows).map_err(|e| row_error(&path, &lines, e))
}

/// Reads a quantum-efficiency table ([`QE_COLUMNS`]; wavelengths strictly increasing, QE in
/// [0, 1], at least two rows; linear between rows, never extrapolated).
///
/// # Errors
/// [`Error::Field`] naming the file, the line and the column for a malformed or invalid value;
/// [`Error::File`] for a missing column or fewer than two rows.
pub fn read_qe_csv(path: &Path) -> Result<QuantumEfficiency> {
    qe_from(CsvReader::open(path)?)
}

/// Parses QE-table CSV bytes ([`read_qe_csv`]); `path` names it in messages.
///
/// # Errors
/// As [`read_qe_csv`].
pub fn parse_qe_csv(bytes: &[u8], path: &Path) -> Result<QuantumEfficiency> {
    qe_from(CsvReader::new(bytes, path)?)
}

fn qe_from<R: BufRead>(reader: CsvReader<R>) -> Result<QuantumEfficiency> {
    let path = reader.path().to_path_buf();
    let (rows, lines) = rows(reader, &QE_COLUMNS, MAX_QE_ROWS)?;
    if rows.len() < 2 {
        return Err(Error::File {
            path,
            message: format!(
                "a quantum-efficiency table needs at least two rows, got {}",
                rows.len()
            ),
        });
    }
    let field = |i: usize, column: &str, message: &str| Error::Field {
        path: path.clone(),
        line: lines[i],
        field: column.to_string(),
        message: message.to_string(),
    };
    for (i, r) in rows.iter().enumerate() {
        if !(r[0].is_finite() && r[0] > 0.0) {
            return Err(field(i, "wavelength_um", "must be finite and > 0 (µm)"));
        }
        if i > 0 && r[0] <= rows[i - 1][0] {
            return Err(field(
                i,
                "wavelength_um",
                "wavelengths must increase strictly from row to row",
            ));
        }
        if !(0.0..=1.0).contains(&r[1]) {
            return Err(field(i, "qe", "must lie in [0, 1]"));
        }
    }
    Ok(QuantumEfficiency::Table(
        rows.iter().map(|r| (r[0], r[1])).collect(),
    ))
}
