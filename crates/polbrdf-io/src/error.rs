//! Errors of the I/O layer.

use std::path::PathBuf;

/// Everything reading or writing a file can fail with. `Display` starts with `path:line:` in
/// the style of compilers, so editors can jump to it.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// The file could not be opened or read.
    #[error("{}: cannot read: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The OS error.
        source: std::io::Error,
    },
    /// The output could not be written (nothing was left at the destination).
    #[error("{}: cannot write: {source}", path.display())]
    Write {
        /// The destination.
        path: PathBuf,
        /// The OS error.
        source: std::io::Error,
    },
    /// Malformed syntax (TOML or CSV) at a line.
    #[error("{}:{line}: {message}", path.display())]
    Syntax {
        /// The file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// A field (TOML key or CSV column) has a bad value at a line.
    #[error("{}:{line}: field `{field}`: {message}", path.display())]
    Field {
        /// The file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// Key or column name.
        field: String,
        /// What is wrong.
        message: String,
    },
    /// A problem with the file as a whole (empty, missing column, no such preset…).
    #[error("{}: {message}", path.display())]
    File {
        /// The file (or the name given on the command line).
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
}

impl Error {
    /// True for errors of the input's content (as opposed to the operating system).
    pub fn is_data_error(&self) -> bool {
        !matches!(self, Error::Read { .. } | Error::Write { .. })
    }

    /// A field error with `more` added to its message (what the reader knows of the field that
    /// the value's parser does not); any other error unchanged.
    pub(crate) fn with_more(self, more: &str) -> Error {
        match self {
            Error::Field {
                path,
                line,
                field,
                message,
            } => Error::Field {
                path,
                line,
                field,
                message: format!("{message}{more}"),
            },
            other => other,
        }
    }
}

/// Shorthand for results of this crate.
pub type Result<T> = std::result::Result<T, Error>;
