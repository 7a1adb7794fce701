//! Where results go: a file written atomically, or standard output.

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
