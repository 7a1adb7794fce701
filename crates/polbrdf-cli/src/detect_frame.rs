//! `polbrdf detect --frame`: the simulated camera frame at the study's best view and first range
//! (`polbrdf_tasks::frame`, docs/detection-frame.md) — its `.npy` arrays and one figure of the
//! raw frame and the reconstructed S0, DoLP and AoLP images, the target outlined.

use crate::error::CliError;
use crate::figures::short;
use crate::output::OutputFile;
use polbrdf::analysis::detection::frame::Frame;
use polbrdf_plot::{nice_ceil, render_files, ColorScale, Colormap, HeatmapFigure, HeatmapPanel};
use polbrdf_plot::{Error as PlotError, Render};
use polbrdf_tasks::detect::DetectStudy;
use polbrdf_tasks::frame::{npy_files, of_study};

/// Simulates the frame of `study` with `seed`; appends its files to `files` and returns the
/// summary line to print once they are written.
pub fn add(
    files: &mut Vec<OutputFile>,
    study: &DetectStudy,
    seed: u64,
) -> Result<String, CliError> {
    let out = of_study(study, None, seed)?;
    let f = &out.frame;
    files.extend(npy_files(f)?);
    let fig = figure(f).map_err(CliError::Plot)?;
    files.extend(
        render_files(&[("frame", &fig as &dyn Render)]).map_err(|(_, e)| CliError::Plot(e))?,
    );
    let view = study.ranked()[0];
    Ok(format!(
        "  frame: θr = {}°, φr = {}°, {} m, seed {seed}: target {}×{} of {}×{} super-pixels \
         ({} pixels on target), {} saturated raw pixels; measured DoLP {:.4} on target, {:.4} \
         on background",
        short(view.theta_r.to_degrees()),
        short(view.phi_r.to_degrees()),
        short(out.detection.range_m),
        f.target_side,
        f.target_side,
        f.side,
        f.side,
        short(out.pixels_on_target),
        f.saturated_pixels(),
        f.target.dolp.mean,
        f.background.dolp.mean,
    ))
}

/// The largest finite value of `v` (0 when none).
fn finite_max(v: &[f64]) -> f64 {
    v.iter()
        .copied()
        .filter(|x| x.is_finite())
        .fold(0.0, f64::max)
}

/// Four panels: the raw counts, S0 (electrons), DoLP and AoLP (cyclic), the target outlined.
pub fn figure(f: &Frame) -> Result<HeatmapFigure, PlotError> {
    let (n, lo) = (f.side, (f.side - f.target_side) / 2);
    let hi = lo + f.target_side;
    let image = |title: &str, side: usize, values: &[f64], scale: ColorScale, k: usize| {
        HeatmapPanel::new(title, side, side, values.to_vec(), scale).map(|mut p| {
            if f.target_side > 0 {
                p.outline = Some([k * lo, k * lo, k * hi, k * hi]);
            }
            p
        })
    };
    let mut aolp = ColorScale::linear(Colormap::Cyclic, -90.0, 90.0, "AoLP (°)");
    aolp.period = Some(180.0);
    aolp.ticks = Some(vec![-90.0, -45.0, 0.0, 45.0, 90.0]);
    Ok(HeatmapFigure {
        panel_size: (620, 560),
        columns: 2,
        panels: vec![
            image(
                "Raw DoFP frame",
                2 * n,
                &f.raw_counts,
                ColorScale::linear(
                    Colormap::Viridis,
                    0.0,
                    nice_ceil(finite_max(&f.raw_counts)),
                    "counts (DN)",
                ),
                2,
            )?,
            image(
                "S0",
                n,
                &f.s0,
                ColorScale::linear(
                    Colormap::Viridis,
                    0.0,
                    nice_ceil(finite_max(&f.s0)),
                    "S0 (e⁻)",
                ),
                1,
            )?,
            image(
                "DoLP",
                n,
                &f.dolp,
                ColorScale::linear(
                    Colormap::Viridis,
                    0.0,
                    nice_ceil(finite_max(&f.dolp)).min(1.0),
                    "DoLP",
                ),
                1,
            )?,
            image("AoLP", n, &f.aolp_deg, aolp, 1)?,
        ],
    })
}
