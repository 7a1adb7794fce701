//! The pieces of the polar maps `map` and `contrast` share (rendering only: the values come
//! from the task layer): grids, marks, colour scales, one-panel figures, rendering to files.

use crate::error::CliError;
use crate::output::OutputFile;
use polbrdf::analysis::contrast::{Illumination, ViewGrid};
use polbrdf_plot::{
    render_files, ColorScale, Colormap, MarkShape, PolarFigure, PolarGrid, PolarMark, PolarPanel,
    Render,
};
use polbrdf_tasks::hemisphere::deg;

/// Size of one map panel, pixels.
pub const PANEL: (u32, u32) = (620, 580);

/// Values on the grid as a plot grid.
pub fn polar_grid(grid: &ViewGrid, values: Vec<f64>) -> Result<PolarGrid, CliError> {
    let theta = grid.thetas().into_iter().map(deg).collect();
    let phi = grid.phis().into_iter().map(deg).collect();
    Ok(PolarGrid::new(theta, phi, values)?)
}

/// The sun and specular marks.
pub fn light_marks(light: &Illumination) -> Vec<PolarMark> {
    let (t, p) = (deg(light.theta_i()), deg(light.phi_i()));
    vec![
        PolarMark {
            theta_deg: t,
            phi_deg: p,
            shape: MarkShape::Sun,
            label: String::new(),
            legend: "sun".into(),
        },
        PolarMark {
            theta_deg: t,
            phi_deg: p + 180.0,
            shape: MarkShape::Specular,
            label: String::new(),
            legend: "specular".into(),
        },
    ]
}

/// The legend of [`invalid_marks`] (`polbrdf map`).
pub const INVALID_LEGEND: &str = "model invalid here (emissivity outside [0, 1])";

/// The short legend of [`invalid_marks`] where the legend row also lists the ranked
/// directions (`polbrdf contrast`: the long one leaves them no room in a 620-pixel panel; the
/// summary line says what the flag is).
pub const INVALID_LEGEND_SHORT: &str = "model invalid here";

/// Marks on the rings of the zeniths (rad) where the model is flagged invalid (issue 36;
/// `polbrdf_tasks::hemisphere::invalid_zeniths`): a dot every 15° of azimuth, with `legend`.
pub fn invalid_marks(zeniths: &[f64], legend: &str) -> Vec<PolarMark> {
    zeniths
        .iter()
        .flat_map(|&t| {
            (0..24).map(move |k| PolarMark {
                theta_deg: deg(t),
                phi_deg: 15.0 * f64::from(k),
                shape: MarkShape::Dot,
                label: String::new(),
                legend: legend.into(),
            })
        })
        .collect()
}

/// DoLP colour scale: viridis over the whole range [0, 1], so maps compare directly.
pub fn dolp_scale() -> ColorScale {
    ColorScale::linear(Colormap::Viridis, 0.0, 1.0, "DoLP")
}

/// A one-panel figure.
pub fn single(panel: PolarPanel) -> PolarFigure {
    PolarFigure {
        panel_size: PANEL,
        columns: 1,
        panels: vec![panel],
    }
}

/// Renders each `(stem, figure)` into `stem.png` and `stem.svg` (in parallel,
/// `polbrdf_plot::render_files`) and appends them to `out` in the given order.
pub fn render_all(
    out: &mut Vec<OutputFile>,
    figures: &[(&str, PolarFigure)],
) -> Result<(), CliError> {
    let list: Vec<(&str, &dyn Render)> = figures
        .iter()
        .map(|(s, f)| (*s, f as &dyn Render))
        .collect();
    out.extend(render_files(&list).map_err(|(_, e)| CliError::Plot(e))?);
    Ok(())
}

/// Log colour limits: the data's range, at most 6 decades deep and at least one.
pub fn log_limits(values: &[f64]) -> (f64, f64) {
    let hi = values
        .iter()
        .copied()
        .filter(|v| v.is_finite())
        .fold(0.0, f64::max);
    let lo = values
        .iter()
        .copied()
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold(f64::INFINITY, f64::min);
    if !(hi > 0.0 && lo.is_finite()) {
        return (0.1, 1.0);
    }
    (lo.clamp(hi * 1e-6, hi * 0.1), hi)
}

/// AoLP-like colour scale over (−90°, 90°] with ticks every 45°.
pub fn angle_scale(colormap: Colormap, label: &str) -> ColorScale {
    ColorScale {
        period: Some(180.0),
        ticks: Some(vec![-90.0, -45.0, 0.0, 45.0, 90.0]),
        ..ColorScale::linear(colormap, -90.0, 90.0, label)
    }
}

/// A number for a title: up to 3 decimals, no trailing zeros.
pub fn short(v: f64) -> String {
    let s = format!("{v:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.to_string()
    }
}

/// The input Stokes vector for a title, empty when unpolarized.
pub fn input_stokes(light: &Illumination, (open, close): (&str, &str)) -> String {
    if light.stokes() == polbrdf::Stokes::unpolarized() {
        return String::new();
    }
    let s = light.stokes().0;
    format!(
        "{open}{}, {}, {}, {}{close}",
        short(s[0]),
        short(s[1]),
        short(s[2]),
        short(s[3])
    )
}
