//! The book's command-line reference, `docs/cli.md`, is generated from the clap definitions
//! (`polbrdf_cli::command()`) by the `clap-markdown` crate. This test fails when the committed
//! file differs from what the code generates, so the reference cannot drift from `--help`.
//! Regenerate it after changing a command or an option (one command, from the repository root):
//!
//! ```sh
//! UPDATE_CLI_REFERENCE=1 cargo test --release -p polbrdf-cli --test cli cli_reference
//! ```

use std::path::Path;

/// The reference as the code defines it.
fn generated() -> String {
    let options = clap_markdown::MarkdownOptions::new()
        .title("Command-line reference".to_string())
        .show_footer(false);
    let body = clap_markdown::help_markdown_command_custom(&polbrdf_cli::command(), &options);
    format!(
        "<!-- Generated from the clap definitions (polbrdf_cli::command) by \
         crates/polbrdf-cli/tests/cli_reference.rs: do not edit. Regenerate with\n     \
         UPDATE_CLI_REFERENCE=1 cargo test --release -p polbrdf-cli --test cli cli_reference -->\n\n\
         {}\n",
        body.trim_end()
    )
}

#[test]
fn cli_reference_matches_the_clap_definitions() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/cli.md");
    let expected = generated();
    if std::env::var_os("UPDATE_CLI_REFERENCE").is_some() {
        std::fs::write(&path, &expected).unwrap();
        return;
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    if committed != expected {
        let line = committed
            .lines()
            .zip(expected.lines())
            .position(|(a, b)| a != b)
            .map_or(
                committed.lines().count().min(expected.lines().count()),
                |i| i,
            )
            + 1;
        panic!(
            "docs/cli.md differs from the clap definitions from line {line} on; regenerate it: \
             UPDATE_CLI_REFERENCE=1 cargo test --release -p polbrdf-cli --test cli cli_reference"
        );
    }
}
