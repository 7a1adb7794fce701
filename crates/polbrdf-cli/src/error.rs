//! The command line's error type and its exit codes (documented in the README and docs/cli.md).

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

    /// A task's refusal of a request field that only options fill (no file content): a usage
    /// error naming the option (exit code 2), like clap's own refusals.
    pub fn usage(e: polbrdf_tasks::TaskError) -> Self {
        match e {
            polbrdf_tasks::TaskError::Invalid { field, message } => {
                CliError::Usage(format!("{}: {}", option_of(&field), with_options(&message)))
            }
            other => other.into(),
        }
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

/// The command-line option of a task request field: `sun_zenith_deg` → `--sun-zenith-deg`.
pub fn option_of(field: &str) -> String {
    format!("--{}", field.replace('_', "-"))
}

/// The request fields that task messages name in backticks (`polbrdf_tasks::TaskError`): only
/// these are shown as options, since a message also quotes model and file words in backticks.
const FIELD_REFERENCES: [&str; 2] = ["wavelength_um", "band"];

/// A task message with the request fields it names in backticks (`` `wavelength_um` ``) shown
/// as options (`--wavelength-um`).
fn with_options(message: &str) -> String {
    let mut out = String::with_capacity(message.len());
    let mut rest = message;
    while let Some(start) = rest.find('`') {
        let Some(len) = rest[start + 1..].find('`') else {
            break;
        };
        let name = &rest[start + 1..start + 1 + len];
        out.push_str(&rest[..start]);
        if FIELD_REFERENCES.contains(&name) {
            out.push_str(&option_of(name));
        } else {
            out.push_str(&rest[start..start + len + 2]);
        }
        rest = &rest[start + len + 2..];
    }
    out.push_str(rest);
    out
}

impl From<polbrdf_tasks::TaskError> for CliError {
    fn from(e: polbrdf_tasks::TaskError) -> Self {
        use polbrdf_tasks::TaskError;
        match e {
            TaskError::Io(e) => CliError::Io(e),
            TaskError::Model(e) => CliError::Model(e),
            TaskError::Fit(e) => CliError::Fit(e),
            TaskError::Invalid { field, message } => {
                CliError::Invalid(format!("{}: {}", option_of(&field), with_options(&message)))
            }
            TaskError::Usage { field, message } => {
                CliError::Usage(format!("{} {}", option_of(&field), with_options(&message)))
            }
            TaskError::Limit { field, what, max } => CliError::Usage(format!(
                "{}{what}: at most {max} (the limit of this option; see \
                 docs/reliability.md)",
                option_of(&field)
            )),
            other => CliError::Invalid(other.to_string()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn task_fields_become_options() {
        assert_eq!(option_of("sun_zenith_deg"), "--sun-zenith-deg");
        assert_eq!(
            with_options("give `wavelength_um` or `band`; the `paper` form, `Keep.This` and `x"),
            "give --wavelength-um or --band; the `paper` form, `Keep.This` and `x"
        );
        let e = CliError::from(polbrdf_tasks::TaskError::invalid(
            "top",
            "must be at least 1",
        ));
        assert_eq!(e.to_string(), "--top: must be at least 1");
        assert_eq!(e.exit_code(), 3);
        let e = CliError::from(polbrdf_tasks::TaskError::usage("target", "is required"));
        assert_eq!(
            (e.to_string().as_str(), e.exit_code()),
            ("--target is required", 2)
        );
    }
}
