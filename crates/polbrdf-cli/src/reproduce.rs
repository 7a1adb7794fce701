//! `polbrdf reproduce`: the paper's figures and Table 1, with a report.

use crate::error::CliError;
use crate::progress::Progress;
use std::path::Path;

/// Runs `polbrdf reproduce`, with a progress bar when standard error is a terminal.
pub fn run(out_dir: &Path) -> Result<(), CliError> {
    let bar = Progress::new(1, "reproduce");
    let opts = polbrdf_reproduce::Options {
        out_dir: out_dir.to_path_buf(),
    };
    let summary = polbrdf_reproduce::run(&opts, &mut |stage, done, total| {
        bar.set(done as u64, total as u64, Some(stage));
    });
    drop(bar);
    let summary = summary?;
    crate::note!(
        "polbrdf reproduce: wrote {} files to {} — open {}:",
        summary.files.len(),
        out_dir.display(),
        out_dir.join("report.md").display()
    );
    for c in &summary.checks {
        crate::note!(
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
