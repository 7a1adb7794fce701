//! The `polbrdf` binary (thin: the `main.rs` of the crate). The command line lives in the library (`polbrdf_cli`), which the Python
//! package's `polbrdf` command calls too.

use std::process::ExitCode;

fn main() -> ExitCode {
    ExitCode::from(polbrdf_cli::main_with_args(std::env::args_os()))
}
