//! The table formats and the one that a path's extension names.

#[cfg(not(feature = "arrow"))]
use crate::error::Error;
use std::path::Path;

/// A table format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Comma-separated text with a header line.
    Csv,
    /// NumPy `.npy` structured array ([`crate::npy`]).
    Npy,
    /// Arrow IPC file format (Feather v2): `.arrow`, `.feather`.
    ArrowFile,
    /// Arrow IPC stream format: `.arrows`.
    ArrowStream,
}

impl Format {
    /// The format a path's extension names (any case): `.npy` is [`Format::Npy`], `.arrow`
    /// and `.feather` [`Format::ArrowFile`], `.arrows` [`Format::ArrowStream`], anything else
    /// (and `-`) CSV.
    pub fn of(path: &Path) -> Format {
        match path.extension().and_then(|e| e.to_str()) {
            Some(e) if e.eq_ignore_ascii_case("npy") => Format::Npy,
            Some(e) if e.eq_ignore_ascii_case("arrow") || e.eq_ignore_ascii_case("feather") => {
                Format::ArrowFile
            }
            Some(e) if e.eq_ignore_ascii_case("arrows") => Format::ArrowStream,
            _ => Format::Csv,
        }
    }

    /// True for the Arrow IPC formats.
    pub fn is_arrow(self) -> bool {
        matches!(self, Format::ArrowFile | Format::ArrowStream)
    }
}

/// The error for an Arrow table in a build without the feature `arrow`.
#[cfg(not(feature = "arrow"))]
pub(super) fn no_arrow(path: &Path) -> Error {
    Error::File {
        path: path.to_path_buf(),
        message: "this build of polbrdf lacks Arrow support (built without the feature `arrow`); \
                  use CSV or .npy, or rebuild with `--features arrow`"
            .into(),
    }
}
