//! Where results go: an output target of `polbrdf_io` (a regular file written atomically, a
//! device, FIFO or `/dev/fd/N` written directly, `-` for standard output), or standard output.

use crate::error::CliError;
use std::io::Write;
use std::path::Path;

/// Writes `bytes` to `output` atomically, or to standard output when `None`.
pub fn write_output(output: Option<&Path>, bytes: &[u8]) -> Result<(), CliError> {
    match output {
        Some(path) => Ok(polbrdf_io::write_atomic(path, bytes)?),
        None => {
            let mut out = std::io::stdout().lock();
            out.write_all(bytes)
                .and_then(|_| out.flush())
                .map_err(CliError::Output)
        }
    }
}

/// Prints a note (a summary, a progress line) on standard error, ignoring a closed or broken
/// standard error: a note is never worth a lost result or an abort.
pub fn note(text: &str) {
    let mut err = std::io::stderr().lock();
    let _ = err.write_all(text.as_bytes()).and_then(|()| err.flush());
}

/// `eprintln!` that never panics: a line on standard error through [`note`].
#[macro_export]
macro_rules! note {
    ($($arg:tt)*) => {
        $crate::output::note(&format!("{}\n", format_args!($($arg)*)))
    };
}

/// A file to write: name in the output directory and content.
pub type OutputFile = (String, Vec<u8>);

/// Creates `dir` and writes every file atomically; returns the paths.
pub fn write_all(dir: &Path, files: &[OutputFile]) -> Result<Vec<std::path::PathBuf>, CliError> {
    Ok(polbrdf_io::write_files(dir, files)?)
}

/// A CSV document from a header and rows of numbers (shortest round-trip form).
pub fn csv(header: &[&str], rows: impl Iterator<Item = Vec<f64>>) -> Vec<u8> {
    let mut t = polbrdf_io::CsvTable::new(header);
    for row in rows {
        t.row(&row);
    }
    t.into_bytes()
}
