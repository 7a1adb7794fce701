//! The crate's error type and atomic file output.

use std::path::{Path, PathBuf};

/// Everything [`crate::run`] can fail with.
#[non_exhaustive]
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// Creating the output directory or writing/renaming a file failed.
    #[error("cannot write {}: {source}", path.display())]
    Io {
        /// The file or directory concerned.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// Drawing a figure failed.
    #[error("cannot draw {}: {message}", path.display())]
    Plot {
        /// The figure file concerned.
        path: PathBuf,
        /// What the plotting library reported.
        message: String,
    },
    /// The embedded font could not be loaded (a build problem, not a user error).
    #[error("the embedded font DejaVuSans.ttf could not be loaded")]
    Font,
    /// The core model refused a parameter (a bug in this crate's constants).
    #[error("model error: {0}")]
    Model(#[from] polbrdf::Error),
}

impl Error {
    /// A plotting error for the figure file `path`.
    pub(crate) fn from_plot(e: polbrdf_plot::Error, path: &Path) -> Self {
        match e {
            polbrdf_plot::Error::Font => Error::Font,
            other => Error::Plot {
                path: path.to_path_buf(),
                message: other.to_string(),
            },
        }
    }
}

/// Writes the files of a run into `dir` as one set (`polbrdf_io::write_files`).
pub fn write_set(dir: &Path, files: &[(String, Vec<u8>)]) -> Result<(), Error> {
    polbrdf_io::write_files(dir, files)
        .map(|_| ())
        .map_err(|e| match e {
            polbrdf_io::Error::Write { path, source } => Error::Io { path, source },
            other => Error::Io {
                path: dir.to_path_buf(),
                source: std::io::Error::other(other.to_string()),
            },
        })
}
