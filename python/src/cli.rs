//! The `polbrdf` command of the Python package: the Rust command line itself
//! (`polbrdf_cli::main_with_args`), so `pip install ./python` gives the same program as
//! `cargo install --path crates/polbrdf-cli`.

use pyo3::prelude::*;

/// Runs the `polbrdf` command line with `argv` (the program name first) and returns its exit
/// code. It runs as the process's main function: it installs the CLI's signal cleanup and panic
/// hook and writes to the process's standard output and error. The GIL is released meanwhile.
#[pyfunction]
pub fn cli_main(py: Python<'_>, argv: Vec<String>) -> u8 {
    py.detach(|| polbrdf_cli::main_with_args(argv))
}
