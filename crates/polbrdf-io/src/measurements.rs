//! Measurement CSV for fitting: the four angle columns plus measured quantities, each optionally
//! with a `sigma_<column>` 1-σ uncertainty.

use crate::csv_io::parse_number;
use crate::error::{Error, Result};
use polbrdf::Geometry;
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
    cols.extend((0..16).map(|k| format!("m{}{}", k / 4, k % 4)));
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
    parse_measurements_csv(&crate::csv_io::read_all(path)?, path)
}

/// Parses the bytes of a measurement CSV; `path` is used in messages only.
///
/// # Errors
/// As [`read_measurements_csv`], except [`Error::Read`].
pub fn parse_measurements_csv(bytes: &[u8], path: &Path) -> Result<MeasurementTable> {
    let crate::GeometryTable {
        headers,
        rows,
        lines,
        geometries,
        wavelengths,
        ..
    } = crate::csv_io::parse_geometry_csv(bytes, path)?;
    let measurable = measurable_columns();
    for h in &headers {
        if let Some(q) = h.strip_prefix("sigma_") {
            if !headers.iter().any(|x| x == q) {
                return Err(Error::File {
                    path: path.to_path_buf(),
                    message: format!("column `{h}` has no column `{q}` to go with"),
                });
            }
        }
    }
    let mut columns = Vec::new();
    for (ci, h) in headers.iter().enumerate() {
        if !measurable.contains(h) {
            continue;
        }
        let si = headers.iter().position(|x| *x == format!("sigma_{h}"));
        let mut values = Vec::with_capacity(rows.len());
        let mut sigmas = si.map(|_| Vec::with_capacity(rows.len()));
        for (row, &line) in rows.iter().zip(&lines) {
            let cell = |k: usize, name: &str| -> Result<Option<f64>> {
                let text = row[k].trim();
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
            };
            let v = cell(ci, h)?;
            values.push(v);
            if let (Some(si), Some(sig)) = (si, sigmas.as_mut()) {
                let name = &headers[si];
                let s = cell(si, name)?;
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
        }
        columns.push(MeasuredColumn {
            name: h.clone(),
            values,
            sigmas,
        });
    }
    if columns.is_empty() {
        return Err(Error::File {
            path: path.to_path_buf(),
            message: format!(
                "no measured column: expected at least one of {}",
                measurable.join(", ")
            ),
        });
    }
    Ok(MeasurementTable {
        path: path.to_path_buf(),
        lines,
        geometries,
        columns,
        wavelengths,
    })
}
