//! The view-direction file: the view zenith and azimuth angles of a radiance or contrast run.

use super::fields::parse_number;
use super::message::show;
use super::reader::{for_each_record, CsvReader};
use crate::error::{Error, Result};
use std::io::BufRead;
use std::path::Path;

/// The columns of a view-direction file: the view zenith and azimuth angles in degrees.
pub const VIEW_COLUMNS: [&str; 2] = ["theta_r_deg", "phi_r_deg"];

/// Reads a view-direction file (CSV with columns `theta_r_deg, phi_r_deg` in any order; other
/// columns are ignored, so a geometry or result table can be reused) and returns the
/// `(θ_r, φ_r)` pairs in degrees, in file order.
///
/// # Errors
/// [`Error::Field`] naming the file, the line and the column for a value that is not a number,
/// a view zenith angle outside [0°, 90°) or a non-finite azimuth; [`Error::File`] for a missing
/// column or a file without rows.
pub fn read_views_csv(path: &Path) -> Result<Vec<(f64, f64)>> {
    views_from(CsvReader::open(path)?)
}

/// Parses view-direction CSV bytes ([`read_views_csv`]); `path` is used in messages only.
///
/// # Errors
/// As [`read_views_csv`].
pub fn parse_views_csv(bytes: &[u8], path: &Path) -> Result<Vec<(f64, f64)>> {
    views_from(CsvReader::new(bytes, path)?)
}

fn views_from<R: BufRead>(mut reader: CsvReader<R>) -> Result<Vec<(f64, f64)>> {
    let index = reader.require(&VIEW_COLUMNS)?;
    let path = reader.path().to_path_buf();
    let path = path.as_path();
    let field = |line: usize, column: &str, message: String| Error::Field {
        path: path.to_path_buf(),
        line,
        field: column.to_string(),
        message,
    };
    let mut views = Vec::new();
    for_each_record(&mut reader, |r| {
        let line = r.line;
        let theta = parse_number(path, line, VIEW_COLUMNS[0], r.get(index[0]))?;
        let phi = parse_number(path, line, VIEW_COLUMNS[1], r.get(index[1]))?;
        if !(0.0..90.0).contains(&theta) {
            return Err(field(
                line,
                VIEW_COLUMNS[0],
                format!("{theta}: the view zenith angle must lie in [0, 90) degrees"),
            ));
        }
        if !(phi.is_finite() && phi.abs() <= polbrdf::MAX_AZIMUTH_DEG) {
            return Err(field(
                line,
                VIEW_COLUMNS[1],
                format!(
                    "{}: must be finite and within ±{}° (beyond it too few digits of the angle \
                     remain)",
                    show(phi),
                    show(polbrdf::MAX_AZIMUTH_DEG)
                ),
            ));
        }
        views.push((theta, phi));
        Ok(())
    })?;
    if views.is_empty() {
        return Err(Error::File {
            path: path.to_path_buf(),
            message: "no view directions (the file has a header but no rows)".into(),
        });
    }
    Ok(views)
}
