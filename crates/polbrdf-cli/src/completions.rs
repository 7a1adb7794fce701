//! `polbrdf completions <shell>`: the shell's completion script for every command and option,
//! generated from the clap definitions (`clap_complete`) and written to standard output through
//! the one output layer.

use crate::error::CliError;
use crate::output;

/// Writes the completion script of `command` (the whole CLI) for `shell`.
pub fn run(shell: clap_complete::Shell, command: &mut clap::Command) -> Result<(), CliError> {
    let mut script = Vec::new();
    clap_complete::generate(shell, command, "polbrdf", &mut script);
    output::write_output(None, &script)
}
