//! `polbrdf reproduce`: the paper's figures and Table 1, with a report.

use crate::error::CliError;
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::path::Path;

/// Runs `polbrdf reproduce`, with a progress bar when standard error is a terminal.
pub fn run(out_dir: &Path) -> Result<(), CliError> {
    let bar = if std::io::stderr().is_terminal() {
        let bar = ProgressBar::new(1);
        bar.set_style(
            ProgressStyle::with_template("{spinner} [{bar:30}] {pos}/{len} {msg}")
                .expect("valid template")
                .progress_chars("=> "),
        );
        Some(bar)
    } else {
        None
    };
    let opts = polbrdf_reproduce::Options {
        out_dir: out_dir.to_path_buf(),
    };
    let summary = polbrdf_reproduce::run(&opts, &mut |stage, done, total| {
        if let Some(bar) = &bar {
            bar.set_length(total as u64);
            bar.set_position(done as u64);
            bar.set_message(stage.to_string());
        }
    });
    if let Some(bar) = &bar {
        bar.finish_and_clear();
    }
    let summary = summary?;
    println!(
        "Wrote {} files to {} — open {}:",
        summary.files.len(),
        out_dir.display(),
        out_dir.join("report.md").display()
    );
    for c in &summary.checks {
        println!(
            "  {} {}",
            if c.confirmed {
                "confirmed:    "
            } else {
                "NOT confirmed:"
            },
            c.claim
        );
    }
    Ok(())
}
