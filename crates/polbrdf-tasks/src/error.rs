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
    /// (the CLI's option name and the Python keyword are derived from it by the adapters).
    #[error("{field}: {message}")]
    Invalid {
        /// The request field.
        field: String,
        /// What is wrong, and what would be accepted.
        message: String,
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
}

/// Shorthand for results of this crate.
pub type TaskResult<T> = Result<T, TaskError>;
