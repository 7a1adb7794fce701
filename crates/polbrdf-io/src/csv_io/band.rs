//! The band file: a relative spectral response by wavelength.

use super::fields::{parse_number, row_error};
use super::reader::CsvReader;
use crate::error::Result;
use std::io::BufRead;
use std::path::Path;

/// The columns of a band file: the wavelength (µm) and the relative spectral response.
pub const BAND_COLUMNS: [&str; 2] = ["wavelength_um", "response"];

/// Reads a band file (CSV with columns `wavelength_um, response`: a relative spectral response,
/// linear between the rows and zero outside, wavelengths strictly increasing).
///
/// # Errors
/// [`Error::Field`] naming the file, the line and the column for a malformed or invalid value;
/// [`Error::File`] for a missing column, fewer than two rows, or a response zero everywhere;
/// [`Error::Field`] at the row after the [`polbrdf::analysis::spectral::MAX_BAND_ROWS`]th
/// (the file is read no further).
///
/// [`Error::Field`]: crate::Error::Field
/// [`Error::File`]: crate::Error::File
pub fn read_band_csv(path: &Path) -> Result<polbrdf::Band> {
    band_from(CsvReader::open(path)?)
}

/// Parses band CSV bytes ([`read_band_csv`]); `path` is used in messages only.
///
/// # Errors
/// As [`read_band_csv`].
pub fn parse_band_csv(bytes: &[u8], path: &Path) -> Result<polbrdf::Band> {
    band_from(CsvReader::new(bytes, path)?)
}

fn band_from<R: BufRead>(mut reader: CsvReader<R>) -> Result<polbrdf::Band> {
    let index = reader.require(&BAND_COLUMNS)?;
    let path = reader.path().to_path_buf();
    let path = path.as_path();
    let (mut wl, mut response, mut lines) = (Vec::new(), Vec::new(), Vec::new());
    // Read up to one row past the core's bound (which names that row): no further.
    while wl.len() <= polbrdf::analysis::spectral::MAX_BAND_ROWS {
        let Some(r) = reader.next_record()? else {
            break;
        };
        wl.push(parse_number(
            path,
            r.line,
            BAND_COLUMNS[0],
            r.get(index[0]),
        )?);
        response.push(parse_number(
            path,
            r.line,
            BAND_COLUMNS[1],
            r.get(index[1]),
        )?);
        lines.push(r.line);
    }
    let name = path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    polbrdf::Band::new(&name, wl, response).map_err(|e| row_error(path, &lines, e))
}
