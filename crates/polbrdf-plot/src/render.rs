//! In-memory rendering: every kind of figure to PNG and SVG bytes ([`Render`]), and many
//! figures at once, in parallel ([`render_files`]).

use crate::error::{Error, Result};
use rayon::prelude::*;

/// A figure that renders itself to a PNG file and an SVG document, in memory.
pub trait Render: Sync {
    /// The PNG file's bytes.
    ///
    /// # Errors
    /// [`Error`] when drawing or encoding fails.
    fn png(&self) -> Result<Vec<u8>>;
    /// The SVG document.
    ///
    /// # Errors
    /// [`Error`] when drawing fails.
    fn svg(&self) -> Result<String>;
}

impl Render for crate::Figure {
    fn png(&self) -> Result<Vec<u8>> {
        crate::Figure::png(self)
    }
    fn svg(&self) -> Result<String> {
        crate::Figure::svg(self)
    }
}

impl Render for crate::PolarFigure {
    fn png(&self) -> Result<Vec<u8>> {
        crate::PolarFigure::png(self)
    }
    fn svg(&self) -> Result<String> {
        crate::PolarFigure::svg(self)
    }
}

impl Render for crate::HeatmapFigure {
    fn png(&self) -> Result<Vec<u8>> {
        crate::HeatmapFigure::png(self)
    }
    fn svg(&self) -> Result<String> {
        crate::HeatmapFigure::svg(self)
    }
}

/// Named files' bytes: `(file name, contents)`.
pub type Files = Vec<(String, Vec<u8>)>;

/// Renders each `(stem, figure)` to `stem.png` and `stem.svg`, in parallel: the file names and
/// their bytes, in the given order (PNG before SVG), ready to be written. The one rendering
/// helper of the project (the command line and `polbrdf reproduce` use it, then write the files
/// atomically).
///
/// # Errors
/// The first figure that fails, with its file name.
pub fn render_files(
    figures: &[(&str, &dyn Render)],
) -> std::result::Result<Files, (String, Error)> {
    let jobs: Vec<(usize, bool)> = (0..figures.len())
        .flat_map(|k| [(k, true), (k, false)])
        .collect();
    jobs.par_iter()
        .map(|&(k, png)| {
            let (stem, fig) = figures[k];
            if png {
                let name = format!("{stem}.png");
                fig.png().map(|b| (name.clone(), b)).map_err(|e| (name, e))
            } else {
                let name = format!("{stem}.svg");
                fig.svg()
                    .map(|s| (name.clone(), s.into_bytes()))
                    .map_err(|e| (name, e))
            }
        })
        .collect()
}
