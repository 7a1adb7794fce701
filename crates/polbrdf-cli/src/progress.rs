//! Progress bars on standard error for the runs that can take more than a few seconds
//! (`reproduce`, `export`, `fit` of a `.pbsdf` table, `lut`, `contrast --scene`, a large
//! `eval`): drawn only when standard error is a terminal, so that logs and pipes get the
//! summaries alone. The task layer reports its
//! progress through a plain closure; the bar lives here.

use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;

/// A bar, or nothing when standard error is not a terminal.
pub struct Progress(Option<ProgressBar>);

impl Progress {
    /// A bar of `len` steps labelled `what`.
    pub fn new(len: u64, what: &str) -> Self {
        if !std::io::stderr().is_terminal() {
            return Progress(None);
        }
        let bar = ProgressBar::new(len);
        bar.set_style(
            ProgressStyle::with_template("{spinner} [{bar:30}] {pos}/{len} {msg} ({eta})")
                .expect("valid template")
                .progress_chars("=> "),
        );
        bar.set_message(what.to_string());
        Progress(Some(bar))
    }

    /// A counter of steps whose total is not known in advance (a CSV table's rows), labelled
    /// `what`; [`Progress::set`] with a `total` of 0 leaves the length open.
    pub fn counter(what: &str) -> Self {
        if !std::io::stderr().is_terminal() {
            return Progress(None);
        }
        let bar = ProgressBar::new_spinner();
        bar.set_style(
            ProgressStyle::with_template("{spinner} {pos} {msg} ({elapsed})")
                .expect("valid template"),
        );
        bar.set_message(what.to_string());
        Progress(Some(bar))
    }

    /// `done` of `total` steps, with the current stage's name.
    pub fn set(&self, done: u64, total: u64, stage: Option<&str>) {
        if let Some(bar) = &self.0 {
            if total > 0 {
                bar.set_length(total);
            }
            bar.set_position(done);
            if let Some(s) = stage {
                bar.set_message(s.to_string());
            }
        }
    }
}

impl Drop for Progress {
    /// The bar is cleared before the summary is printed (and on an error).
    fn drop(&mut self) {
        if let Some(bar) = &self.0 {
            bar.finish_and_clear();
        }
    }
}
