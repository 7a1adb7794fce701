//! # polbrdf-reproduce — the figures and Table 1 of Zhuansun et al. (2015), with a report
//!
//! [`run`] recomputes, with the `polbrdf` core crate, everything the paper's §3–4 show, and
//! writes into [`Options::out_dir`]:
//!
//! | file | content | CSV columns |
//! |---|---|---|
//! | `fig2.{png,svg,csv}` | scalar BRDF (eq. 6) vs θN at in-plane specular geometry | `theta_deg,thetaN_deg,brdf` |
//! | `fig3.{png,svg,csv}` | DoLP vs incidence angle, smooth surface | `theta_deg,dolp` |
//! | `fig4.{png,svg,csv}` | DoLP vs incidence angle for roughness 0 … 0.5 | `theta_deg,roughness,dolp` |
//! | `fig5.{png,svg}`, `table1.csv` | our DoLP beside the paper's Table 1 | `roughness,theta_deg,dolp_model_pct,dolp_paper_model_pct,dolp_paper_lawrence_pct,diff_vs_paper_model_pct,diff_vs_paper_lawrence_pct` |
//! | `report.md` | the figures, every parameter, and a verdict with numbers on each claim | |
//!
//! The files are written as one set (`polbrdf_io::write_files`: staged, moved into place, the
//! completion marker `_COMPLETE` last).
//!
//! What "roughness" means in Fig. 4 and Table 1 is a decision this crate has to make (the
//! paper does not say, and in this model the specular DoLP does not depend on the facet
//! distribution at all): see [`params`], [`compute::Roughness`] and the generated report.
//!
//! ```no_run
//! let opts = polbrdf_reproduce::Options { out_dir: "repro".into() };
//! let summary = polbrdf_reproduce::run(&opts, &mut |stage, done, total| {
//!     eprintln!("[{done}/{total}] {stage}");
//! })?;
//! for c in &summary.checks {
//!     println!("{} {}", if c.confirmed { "✓" } else { "✗" }, c.claim);
//! }
//! # Ok::<(), polbrdf_reproduce::Error>(())
//! ```

#![warn(missing_docs)]

pub mod analysis;
pub mod compute;
mod figures;
mod output;
pub mod params;
mod report;

pub use output::Error;

use params::*;
use std::path::PathBuf;

/// Where to write.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Options {
    /// Output directory; created (with parents) if missing.
    pub out_dir: PathBuf,
}

/// What [`run`] produced.
#[derive(Debug, Clone, PartialEq)]
pub struct Summary {
    /// Every file written, in the order written.
    pub files: Vec<PathBuf>,
    /// One verdict per claim of the paper's §3–4.
    pub checks: Vec<Check>,
}

/// The verdict on one claim of the paper.
#[derive(Debug, Clone, PartialEq)]
pub struct Check {
    /// The claim, in one sentence.
    pub claim: String,
    /// Whether our computation confirms it.
    pub confirmed: bool,
    /// The numbers that decide it.
    pub evidence: String,
}

/// Recomputes everything and writes the files listed in the crate documentation into
/// `opts.out_dir`. `progress(stage, done, total)` is called as the work advances (`done` runs
/// from 0 to `total`).
///
/// # Errors
/// [`Error::Io`] naming the path when the directory cannot be created or a file cannot be
/// written; [`Error::Plot`] when a figure cannot be drawn.
pub fn run(opts: &Options, progress: &mut dyn FnMut(&str, usize, usize)) -> Result<Summary, Error> {
    let dir = &opts.out_dir;
    std::fs::create_dir_all(dir).map_err(|source| Error::Io {
        path: dir.clone(),
        source,
    })?;
    let total = analysis::STEPS + 5;
    let mut done = 0;
    progress("computing", done, total);
    let a = analysis::analyze(&mut |stage| {
        done += 1;
        progress(stage, done, total);
    })?;

    // The set of files, written together at the end (polbrdf_io::write_files).
    let mut set: Vec<(String, Vec<u8>)> = Vec::new();
    let mut files = Vec::new();
    let mut step = |stage: &str, files: &mut Vec<PathBuf>, new: Vec<PathBuf>| {
        files.extend(new);
        done += 1;
        progress(stage, done, total);
    };

    // Fig. 2
    let mut csv = polbrdf_io::CsvTable::new(["theta_deg", "thetaN_deg", "brdf"]);
    for (t, c) in a.fig2.thetas_deg.iter().zip(&a.fig2.brdf) {
        for (tn, f) in a.fig2.theta_n_deg.iter().zip(c) {
            csv.row(&[*t, *tn, *f]);
        }
    }
    let mut new = vec![write(&mut set, dir, "fig2.csv", &csv.into_bytes())?];
    new.extend(render(&mut set, &figures::fig2(&a), dir, "fig2")?);
    step("Fig. 2 written", &mut files, new);

    // Fig. 3
    let mut csv = polbrdf_io::CsvTable::new(["theta_deg", "dolp"]);
    for &(t, d) in &a.fig3 {
        csv.row(&[t, d]);
    }
    let mut new = vec![write(&mut set, dir, "fig3.csv", &csv.into_bytes())?];
    new.extend(render(&mut set, &figures::fig3(&a), dir, "fig3")?);
    step("Fig. 3 written", &mut files, new);

    // Fig. 4
    let mut csv = polbrdf_io::CsvTable::new(["theta_deg", "roughness", "dolp"]);
    for (r, c) in ROUGHNESS.iter().zip(&a.fig4) {
        for (t, d) in a.dolp_angles.iter().zip(c) {
            csv.row(&[*t, *r, *d]);
        }
    }
    let mut new = vec![write(&mut set, dir, "fig4.csv", &csv.into_bytes())?];
    new.extend(render(&mut set, &figures::fig4(&a), dir, "fig4")?);
    step("Fig. 4 written", &mut files, new);

    // Table 1 and Fig. 5
    let mut csv = polbrdf_io::CsvTable::new([
        "roughness",
        "theta_deg",
        "dolp_model_pct",
        "dolp_paper_model_pct",
        "dolp_paper_lawrence_pct",
        "diff_vs_paper_model_pct",
        "diff_vs_paper_lawrence_pct",
    ]);
    let cells = &a.primary().cells;
    for (ri, r) in ROUGHNESS.iter().enumerate() {
        for (ci, t) in TABLE_ANGLES_DEG.iter().enumerate() {
            let ours = round6(cells[ri][ci]);
            let pm = TABLE_PAPER_MODEL[ri][ci];
            let pl = TABLE_PAPER_LAWRENCE[ri][ci];
            csv.row(&[*r, *t, ours, pm, pl, round6(ours - pm), round6(ours - pl)]);
        }
    }
    let mut new = vec![write(&mut set, dir, "table1.csv", &csv.into_bytes())?];
    new.extend(render(&mut set, &figures::fig5(&a), dir, "fig5")?);
    step("Table 1 and Fig. 5 written", &mut files, new);

    // Report
    let checks = report::checks(&a);
    let text = report::markdown(&a, &checks);
    let new = vec![write(&mut set, dir, "report.md", text.as_bytes())?];
    step("report written", &mut files, new);

    output::write_set(dir, &set)?;
    Ok(Summary { files, checks })
}

/// Draws `fig` as `dir/stem.png` and `dir/stem.svg` (rendered in memory by `polbrdf_plot`)
/// into the set; returns both paths.
fn render(
    set: &mut Vec<(String, Vec<u8>)>,
    fig: &polbrdf_plot::Figure,
    dir: &std::path::Path,
    stem: &str,
) -> Result<Vec<PathBuf>, Error> {
    let files = polbrdf_plot::render_files(&[(stem, fig)])
        .map_err(|(name, e)| Error::from_plot(e, &dir.join(name)))?;
    files
        .iter()
        .map(|(name, bytes)| write(set, dir, name, bytes))
        .collect()
}

/// Adds a file to the set; returns its path-to-be.
fn write(
    set: &mut Vec<(String, Vec<u8>)>,
    dir: &std::path::Path,
    name: &str,
    bytes: &[u8],
) -> Result<PathBuf, Error> {
    set.push((name.to_string(), bytes.to_vec()));
    Ok(dir.join(name))
}

/// Rounds to 6 decimals (percentages in table1.csv).
fn round6(x: f64) -> f64 {
    (x * 1e6).round() / 1e6
}
