//! The command line's error type and its exit codes (documented in the README).

/// What can go wrong, each kind with its exit code.
#[derive(Debug)]
pub enum CliError {
    Io(polbrdf_io::Error),
    Model(polbrdf::Error),
    Output(std::io::Error),
    Fit(polbrdf_fit::FitError),
    /// `polbrdf check` found a violation (already printed).
    CheckFailed,
    Reproduce(polbrdf_reproduce::Error),
    /// The fit ran but did not converge: results were written, flagged.
    NotConverged(String),
    /// A command-line value is malformed or out of range (the message names the option).
    Invalid(String),
    /// A required option is missing, or options that exclude each other are combined (what
    /// clap cannot check by itself).
    Usage(String),
    /// A figure could not be drawn (a bug: the figures are built from validated data).
    Plot(polbrdf_plot::Error),
}

impl CliError {
    /// A write to a closed standard output (or pipe): ends the command quietly with 141.
    pub fn is_broken_pipe(&self) -> bool {
        let io = match self {
            CliError::Output(e) => Some(e),
            CliError::Io(polbrdf_io::Error::Write { source, path }) if path.as_os_str() == "-" => {
                Some(source)
            }
            _ => None,
        };
        io.is_some_and(|e| e.kind() == std::io::ErrorKind::BrokenPipe)
    }

    pub fn exit_code(&self) -> u8 {
        match self {
            CliError::Io(e) if e.is_data_error() => 3,
            CliError::Io(_) => 4,
            CliError::Model(_) => 3,
            CliError::Output(_) => 4,
            CliError::Fit(_) => 3,
            CliError::CheckFailed => 6,
            CliError::Reproduce(polbrdf_reproduce::Error::Io { .. }) => 4,
            CliError::Reproduce(_) => 1,
            CliError::NotConverged(_) => 5,
            CliError::Invalid(_) => 3,
            CliError::Usage(_) => 2,
            CliError::Plot(_) => 1,
        }
    }
}

impl std::fmt::Display for CliError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CliError::Io(e) => write!(f, "{e}"),
            CliError::Model(e) => write!(f, "{e}"),
            CliError::Output(e) => write!(f, "cannot write to standard output: {e}"),
            CliError::Fit(e) => write!(f, "fit: {e}"),
            CliError::CheckFailed => write!(f, "check: the parameter set is not physically valid everywhere (see above)"),
            CliError::Reproduce(e) => write!(f, "reproduce: {e}"),
            CliError::Invalid(m) | CliError::Usage(m) => write!(f, "{m}"),
            CliError::Plot(e) => write!(f, "figure: {e}"),
            CliError::NotConverged(m) => write!(
                f,
                "fit did not converge ({m}); the results were written with \"converged\": false — \
                 try better start values in the material file, more --starts, or fewer free parameters"
            ),
        }
    }
}

impl From<polbrdf_io::Error> for CliError {
    fn from(e: polbrdf_io::Error) -> Self {
        CliError::Io(e)
    }
}

impl From<polbrdf::Error> for CliError {
    fn from(e: polbrdf::Error) -> Self {
        CliError::Model(e)
    }
}

impl From<polbrdf_fit::FitError> for CliError {
    fn from(e: polbrdf_fit::FitError) -> Self {
        CliError::Fit(e)
    }
}

impl From<polbrdf_reproduce::Error> for CliError {
    fn from(e: polbrdf_reproduce::Error) -> Self {
        CliError::Reproduce(e)
    }
}

impl From<polbrdf_plot::Error> for CliError {
    fn from(e: polbrdf_plot::Error) -> Self {
        CliError::Plot(e)
    }
}

impl From<polbrdf_tasks::TaskError> for CliError {
    fn from(e: polbrdf_tasks::TaskError) -> Self {
        use polbrdf_tasks::TaskError;
        match e {
            TaskError::Io(e) => CliError::Io(e),
            TaskError::Model(e) => CliError::Model(e),
            TaskError::Fit(e) => CliError::Fit(e),
            // The request's field is the option's name with `-` for `_`.
            TaskError::Invalid { field, message } => {
                CliError::Invalid(format!("--{}: {message}", field.replace('_', "-")))
            }
            e => CliError::Invalid(e.to_string()),
        }
    }
}
