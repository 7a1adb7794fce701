//! A table's header and fields checked: the required columns found in the header, a field read
//! as a number, a core error about one row placed at that row's line.

use super::message::{cut, short_list, short_name};
use crate::error::{Error, Result};
use std::path::Path;

/// Parses a number in a CSV field (surrounding whitespace allowed).
pub(crate) fn parse_number(path: &Path, line: usize, column: &str, field: &str) -> Result<f64> {
    field.trim().parse::<f64>().map_err(|_| Error::Field {
        path: path.to_path_buf(),
        line,
        field: column.to_string(),
        message: format!("expected a number, got {:?}", cut(field, 40)),
    })
}
/// Checks a table's header (CSV or `.npy`): not empty, no column twice, every `required` column
/// present; returns the index of each required column.
pub(crate) fn check_header(
    headers: &[String],
    path: &Path,
    required: &[&str],
) -> Result<Vec<usize>> {
    if headers.is_empty() || headers.iter().all(String::is_empty) {
        return Err(Error::File {
            path: path.to_path_buf(),
            message: format!(
                "empty file: expected a header line naming the columns {}",
                required.join(", ")
            ),
        });
    }
    let mut seen = std::collections::HashSet::with_capacity(headers.len());
    if let Some(h) = headers.iter().find(|h| !seen.insert(h.as_str())) {
        return Err(Error::Syntax {
            path: path.to_path_buf(),
            line: 1,
            message: format!("column `{}` appears twice in the header", short_name(h)),
        });
    }
    let position = |r: &str| headers.iter().position(|h| h == r);
    let missing: Vec<&str> = required
        .iter()
        .copied()
        .filter(|r| position(r).is_none())
        .collect();
    if missing.len() == required.len() {
        // Not a table of this kind (a scene may name any file, `/etc/passwd`): its first line
        // is not shown.
        return Err(Error::File {
            path: path.to_path_buf(),
            message: format!(
                "missing column(s) {}: the first line names none of them, so this is not a \
                 table of that kind (its content is not shown)",
                missing.join(", "),
            ),
        });
    }
    if !missing.is_empty() {
        return Err(Error::File {
            path: path.to_path_buf(),
            message: format!(
                "missing column(s) {} (the header has: {})",
                missing.join(", "),
                short_list(headers)
            ),
        });
    }
    Ok(required
        .iter()
        .map(|r| position(r).expect("checked above"))
        .collect())
}
/// A core error about the row `index` of a table (`InvalidParameterAt`) at that row's line;
/// any other as an error of the whole file.
pub(crate) fn row_error(path: &Path, lines: &[usize], e: polbrdf::Error) -> Error {
    match e {
        polbrdf::Error::InvalidParameterAt { name, index, .. } => Error::Field {
            path: path.to_path_buf(),
            line: lines[index],
            field: name.to_string(),
            message: e.to_string(),
        },
        other => Error::File {
            path: path.to_path_buf(),
            message: other.to_string(),
        },
    }
}
