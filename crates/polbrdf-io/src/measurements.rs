//! Measurement CSV for fitting: the four angle columns plus measured quantities, each optionally
//! with a `sigma_<column>` 1-σ uncertainty.

use crate::csv_io::{
    parse_number, record_geometry, record_wavelength, short_name, CsvReader, Record, ANGLE_COLUMNS,
    WAVELENGTH_COLUMN,
};
use crate::error::{Error, Result};
use polbrdf::Geometry;
use std::io::BufRead;
use std::path::{Path, PathBuf};

/// Names of the quantities a measurement file may hold: `brdf`, `dolp`, `brdf_s`, `brdf_p`
/// (s- and p-polarized incidence, no analyzer: `F00 ± F01`), `m00` … `m33`.
pub fn measurable_columns() -> Vec<String> {
    let mut cols = vec![
        "brdf".to_string(),
        "dolp".into(),
        "brdf_s".into(),
        "brdf_p".into(),
    ];
    cols.extend(polbrdf::Mueller::COLUMNS.map(String::from));
    cols
}

/// One measured column: its values and optional uncertainties, `None` where a row leaves the
/// cell empty (not measured in that row).
#[derive(Debug, Clone)]
pub struct MeasuredColumn {
    /// `brdf`, `dolp`, `brdf_s`, `brdf_p` or `mIJ`.
    pub name: String,
    /// One entry per row.
    pub values: Vec<Option<f64>>,
    /// From `sigma_<name>`, if that column exists; one entry per row.
    pub sigmas: Option<Vec<Option<f64>>>,
}

/// A parsed measurement file.
#[derive(Debug, Clone)]
pub struct MeasurementTable {
    /// Where it came from.
    pub path: PathBuf,
    /// 1-based line of each row.
    pub lines: Vec<usize>,
    /// One geometry per row.
    pub geometries: Vec<Geometry>,
    /// Every measured column present, in file order.
    pub columns: Vec<MeasuredColumn>,
    /// The `wavelength_um` of each row (µm), when the file has that column.
    pub wavelengths: Option<Vec<f64>>,
}

/// Reads a measurement CSV. Columns other than the angles, the measurable quantities and their
/// `sigma_` companions are ignored (e.g. a label). An empty cell means "not measured in this
/// row"; anything else must be a finite number, and a `sigma_` value must be `> 0` and present
/// wherever its quantity is.
///
/// # Errors
/// As [`crate::read_geometry_csv`], plus [`Error::Field`] for a bad value or uncertainty with its
/// line, and [`Error::File`] when no measured column is present or a `sigma_` column has no
/// quantity.
pub fn read_measurements_csv(path: &Path) -> Result<MeasurementTable> {
    measurements_from(CsvReader::open(path)?)
}

/// Parses the bytes of a measurement CSV; `path` is used in messages only.
///
/// # Errors
/// As [`read_measurements_csv`], except [`Error::Read`].
pub fn parse_measurements_csv(bytes: &[u8], path: &Path) -> Result<MeasurementTable> {
    measurements_from(CsvReader::new(bytes, path)?)
}

/// Memory a measurement table holds per row, in bytes, at most: the line number, the geometry,
/// the wavelength and, per measured column, a value and an uncertainty. The rows are read as a
/// stream and kept as columns of numbers (no text), so a file of `N` rows with `c` measured
/// columns needs about `N·(8 + size_of::<Geometry>() + 8 + 32·c)` bytes.
pub fn bytes_per_row(measured_columns: usize) -> usize {
    size_of::<usize>()
        + size_of::<Geometry>()
        + size_of::<f64>()
        + measured_columns * 2 * size_of::<Option<f64>>()
}

/// How many σ a measured value may lie outside its physical range (noise): 5σ, which Gaussian
/// noise exceeds in 3·10⁻⁷ of the values.
pub const NOISE_MARGIN_SIGMAS: f64 = 5.0;

/// The physical range of a measured quantity: every BRDF-like quantity (`brdf`, `brdf_s`,
/// `brdf_p`, `m00`: a reflected radiance per unit irradiance) is ≥ 0, a degree of linear
/// polarization lies in [0, 1]; the other Mueller entries may have either sign. With an
/// uncertainty `sigma`, a value within [`NOISE_MARGIN_SIGMAS`]·σ outside the range is noise and
/// kept; without one, the range is exact.
fn check_physical(name: &str, v: f64, sigma: Option<f64>) -> std::result::Result<(), String> {
    let margin = sigma.map_or(0.0, |s| NOISE_MARGIN_SIGMAS * s);
    let note = if sigma.is_some() {
        ", also allowing 5σ of noise"
    } else {
        " (no σ given: no allowance for noise)"
    };
    match name {
        "brdf" | "brdf_s" | "brdf_p" | "m00" if v < -margin => Err(format!(
            "{v}: a BRDF is ≥ 0 (sr⁻¹){note}; a negative value is not a measurement of a \
             reflectance"
        )),
        "dolp" if !(-margin..=1.0 + margin).contains(&v) => Err(format!(
            "{v}: a degree of linear polarization lies in [0, 1]{note}"
        )),
        _ => Ok(()),
    }
}

/// The measurement table of a CSV reader: its measured columns ([`measured_columns`]), then
/// row by row the geometry, the wavelength (when there is that column) and the measured cells
/// ([`push_cell`]).
fn measurements_from<R: BufRead>(mut reader: CsvReader<R>) -> Result<MeasurementTable> {
    let idx = reader.require(&ANGLE_COLUMNS)?;
    let path = reader.path().to_path_buf();
    let path = path.as_path();
    let headers = reader.headers().to_vec();
    let measured = measured_columns(path, &headers)?;
    let wl = headers.iter().position(|h| h == WAVELENGTH_COLUMN);
    let mut columns: Vec<MeasuredColumn> = measured
        .iter()
        .map(|&(ci, si)| MeasuredColumn {
            name: headers[ci].clone(),
            values: Vec::new(),
            sigmas: si.map(|_| Vec::new()),
        })
        .collect();
    let (mut lines, mut geometries) = (Vec::new(), Vec::new());
    let mut wavelengths = wl.map(|_| Vec::new());
    while let Some(r) = reader.next_record()? {
        geometries.push(record_geometry(path, &r, &idx)?);
        if let (Some(c), Some(w)) = (wl, wavelengths.as_mut()) {
            w.push(record_wavelength(path, &r, c)?);
        }
        lines.push(r.line);
        let row = Row {
            path,
            record: &r,
            headers: &headers,
        };
        for (column, &(ci, si)) in columns.iter_mut().zip(&measured) {
            push_cell(&row, column, ci, si)?;
        }
    }
    Ok(MeasurementTable {
        path: path.to_path_buf(),
        lines,
        geometries,
        columns,
        wavelengths,
    })
}

/// (column index, `sigma_` column index) of each measured column of `headers`, in file order:
/// at least one, and every `sigma_` column with its quantity.
fn measured_columns(path: &Path, headers: &[String]) -> Result<Vec<(usize, Option<usize>)>> {
    let measurable = measurable_columns();
    for h in headers {
        if let Some(q) = h.strip_prefix("sigma_") {
            if !headers.iter().any(|x| x == q) {
                return Err(Error::File {
                    path: path.to_path_buf(),
                    message: format!(
                        "column `{}` has no column `{}` to go with",
                        short_name(h),
                        short_name(q)
                    ),
                });
            }
        }
    }
    let measured: Vec<(usize, Option<usize>)> = headers
        .iter()
        .enumerate()
        .filter(|(_, h)| measurable.contains(h))
        .map(|(ci, h)| {
            let sigma = format!("sigma_{h}");
            (ci, headers.iter().position(|x| *x == sigma))
        })
        .collect();
    if measured.is_empty() {
        return Err(Error::File {
            path: path.to_path_buf(),
            message: format!(
                "no measured column: expected at least one of {}",
                measurable.join(", ")
            ),
        });
    }
    Ok(measured)
}

/// A row of a measurement file, with what its errors name.
struct Row<'a> {
    path: &'a Path,
    record: &'a Record<'a>,
    headers: &'a [String],
}

impl Row<'_> {
    /// The number in column `k`: `None` for an empty cell, else finite.
    fn cell(&self, k: usize) -> Result<Option<f64>> {
        let (path, line) = (self.path, self.record.line);
        let name = &self.headers[k];
        let text = self.record.get(k).trim();
        if text.is_empty() {
            return Ok(None);
        }
        let v = parse_number(path, line, name, text)?;
        if !v.is_finite() {
            return Err(Error::Field {
                path: path.to_path_buf(),
                line,
                field: name.to_string(),
                message: format!("must be finite, got {v}"),
            });
        }
        Ok(Some(v))
    }
}

/// Appends the row's cell of measured column `ci` (its `sigma_` column `si`) to `column`: the
/// value within its physical range ([`check_physical`]), and its uncertainty, which must be
/// > 0 and present wherever the value is.
fn push_cell(
    row: &Row<'_>,
    column: &mut MeasuredColumn,
    ci: usize,
    si: Option<usize>,
) -> Result<()> {
    let (path, line) = (row.path, row.record.line);
    let h = &row.headers[ci];
    let v = row.cell(ci)?;
    let s = si.map(|k| row.cell(k)).transpose()?.flatten();
    if let Some(v) = v {
        check_physical(h, v, s.filter(|s| *s > 0.0)).map_err(|message| Error::Field {
            path: path.to_path_buf(),
            line,
            field: h.clone(),
            message,
        })?;
    }
    column.values.push(v);
    if let (Some(si), Some(sig)) = (si, column.sigmas.as_mut()) {
        let name = &row.headers[si];
        match (v, s) {
            (Some(_), None) => {
                return Err(Error::Field {
                    path: path.to_path_buf(),
                    line,
                    field: name.clone(),
                    message: format!("missing: `{h}` has a value in this row"),
                })
            }
            (_, Some(s)) if s <= 0.0 => {
                return Err(Error::Field {
                    path: path.to_path_buf(),
                    line,
                    field: name.clone(),
                    message: format!("an uncertainty must be > 0, got {s}"),
                })
            }
            _ => {}
        }
        sig.push(s);
    }
    Ok(())
}
