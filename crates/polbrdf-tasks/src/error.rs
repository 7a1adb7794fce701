//! The task layer's error: what a job can fail with, kept apart by its cause so that each adapter
//! can map it (the CLI to its exit codes, Python to its exception types).

/// Everything a job can fail with.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum TaskError {
    /// A file could not be read or written, or its content is invalid (names file, line, field).
    #[error(transparent)]
    Io(#[from] polbrdf_io::Error),
    /// The model refused a parameter or a geometry.
    #[error(transparent)]
    Model(#[from] polbrdf::Error),
    /// A fit could not be set up or run.
    #[error("fit: {0}")]
    Fit(#[from] polbrdf_fit::FitError),
    /// A value of the request is malformed or out of range. `field` is the request's name for it
    /// (the CLI's option name and the Python keyword are derived from it by the adapters); the
    /// message names other request fields in backticks (`` `wavelength_um` ``), for the adapters
    /// to show as theirs.
    #[error("{field}: {message}")]
    Invalid {
        /// The request field.
        field: String,
        /// What is wrong, and what would be accepted.
        message: String,
    },
    /// A required value is missing, or values that exclude each other are combined (the CLI's
    /// usage error). `field` as for [`TaskError::Invalid`].
    #[error("{field}: {message}")]
    Usage {
        /// The request field.
        field: String,
        /// What is missing, and what would be accepted.
        message: String,
    },
    /// A size over its limit (`crate::limits`): the CLI's usage error naming the option, a
    /// Python `ValueError` naming the keyword.
    #[error("{field}{what}: at most {max}")]
    Limit {
        /// The request field.
        field: String,
        /// The value or count asked for, as a suffix of the field (` = 1001`, `: 5 values`).
        what: String,
        /// The limit.
        max: usize,
    },
}

impl TaskError {
    /// A request value out of range or malformed.
    pub fn invalid(field: impl Into<String>, message: impl Into<String>) -> Self {
        TaskError::Invalid {
            field: field.into(),
            message: message.into(),
        }
    }

    /// A required request value is missing.
    pub fn usage(field: impl Into<String>, message: impl Into<String>) -> Self {
        TaskError::Usage {
            field: field.into(),
            message: message.into(),
        }
    }
}

/// Shorthand for results of this crate.
pub type TaskResult<T> = Result<T, TaskError>;
