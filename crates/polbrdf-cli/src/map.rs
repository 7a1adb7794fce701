//! `polbrdf map`: hemispherical maps (polar plots) of the BRDF, DoLP and AoLP of one material
//! for a given illumination; also the pieces `polbrdf contrast` shares (illumination and grid
//! options, material loading, polar panels, output directory).

use crate::error::CliError;
use crate::spectrum::{describe, load_spec, materials_at, SpectralArgs};
use polbrdf::analysis::contrast::{hemisphere_mean, Illumination, ViewGrid, ViewSample};
use polbrdf::{Material, Stokes};
use polbrdf_io::CsvTable;
use polbrdf_plot::{
    render_files, ColorScale, Colormap, MarkShape, PolarFigure, PolarGrid, PolarMark, PolarPanel,
    Render,
};
use std::path::{Path, PathBuf};

/// Size of one map panel, pixels.
pub const PANEL: (u32, u32) = (620, 580);

/// Illumination and viewing grid, shared by `map` and `contrast`.
#[derive(clap::Args, Debug)]
pub struct ViewArgs {
    /// Zenith angle of the source (sun), degrees, in [0, 90) (required, except for `contrast
    /// --scene`).
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    pub sun_zenith_deg: Option<f64>,
    /// Azimuth of the source, degrees (the specular direction is at azimuth + 180°).
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 0.0,
        allow_negative_numbers = true
    )]
    pub sun_azimuth_deg: f64,
    /// Viewing grid steps in degrees: `DTHETA,DPHI`, or one value for both. Zenith angles run
    /// from 0 in steps of DTHETA below 90°; the azimuth step is rounded to divide 360°.
    #[arg(
        long,
        value_name = "DTHETA[,DPHI]",
        default_value = "1,2",
        allow_hyphen_values = true
    )]
    pub grid_deg: String,
    /// Input Stokes vector `S0,S1,S2,S3` (psps basis of the incident beam; normalized to
    /// S0 = 1). Default: unpolarized, 1,0,0,0.
    #[arg(long, value_name = "S0,S1,S2,S3", allow_hyphen_values = true)]
    pub stokes: Option<String>,
    #[command(flatten)]
    pub spectral: SpectralArgs,
}

impl ViewArgs {
    /// The validated illumination and grid.
    pub fn build(&self) -> Result<(Illumination, ViewGrid), CliError> {
        let stokes = match &self.stokes {
            Some(s) => parse_stokes(s)?,
            None => Stokes::unpolarized(),
        };
        let Some(zenith) = self.sun_zenith_deg else {
            return Err(CliError::Usage(
                "--sun-zenith-deg is required (the zenith angle of the source, degrees)".into(),
            ));
        };
        let light = Illumination::from_degrees(zenith, self.sun_azimuth_deg, stokes)?;
        let grid = self.grid()?;
        Ok((light, grid))
    }

    /// The validated viewing grid.
    pub fn grid(&self) -> Result<ViewGrid, CliError> {
        parse_grid(&self.grid_deg)
    }
}

fn numbers(text: &str, option: &str, what: &str) -> Result<Vec<f64>, CliError> {
    text.split(',')
        .map(|t| {
            t.trim().parse::<f64>().map_err(|_| {
                CliError::Invalid(format!(
                    "{option} {text:?}: {t:?} is not a number (expected {what})"
                ))
            })
        })
        .collect()
}

/// `--grid-deg`: one or two steps in degrees.
pub fn parse_grid(text: &str) -> Result<ViewGrid, CliError> {
    let v = numbers(text, "--grid-deg", "DTHETA or DTHETA,DPHI in degrees")?;
    let (a, b) = match v[..] {
        [a] => (a, a),
        [a, b] => (a, b),
        _ => {
            return Err(CliError::Invalid(format!(
                "--grid-deg {text:?}: expected DTHETA or DTHETA,DPHI in degrees"
            )))
        }
    };
    Ok(ViewGrid::from_degrees(a, b)?)
}

/// `--stokes`: four numbers.
pub fn parse_stokes(text: &str) -> Result<Stokes, CliError> {
    match numbers(text, "--stokes", "S0,S1,S2,S3")?[..] {
        [s0, s1, s2, s3] => Ok(Stokes([s0, s1, s2, s3])),
        _ => Err(CliError::Invalid(format!(
            "--stokes {text:?}: expected four numbers S0,S1,S2,S3"
        ))),
    }
}

/// A grid angle (rad) in degrees, rounded to 1e-9° so that grid nodes print exactly.
pub fn deg(x: f64) -> f64 {
    let d = (x.to_degrees() * 1e9).round() / 1e9;
    d + 0.0
}

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

/// A file to write: name in the output directory and content.
pub type Output = (String, Vec<u8>);

/// Renders each `(stem, figure)` into `stem.png` and `stem.svg` (in parallel,
/// `polbrdf_plot::render_files`) and appends them to `out` in the given order.
pub fn render_all(out: &mut Vec<Output>, figures: &[(&str, PolarFigure)]) -> Result<(), CliError> {
    let list: Vec<(&str, &dyn Render)> = figures
        .iter()
        .map(|(s, f)| (*s, f as &dyn Render))
        .collect();
    out.extend(render_files(&list).map_err(|(_, e)| CliError::Plot(e))?);
    Ok(())
}

/// Creates `dir` and writes every file atomically; returns the paths.
pub fn write_all(dir: &Path, files: &[Output]) -> Result<Vec<PathBuf>, CliError> {
    Ok(polbrdf_io::write_files(dir, files)?)
}

/// A CSV document from a header and rows of numbers (shortest round-trip form).
pub fn csv(header: &[&str], rows: impl Iterator<Item = Vec<f64>>) -> Vec<u8> {
    let mut t = CsvTable::new(header);
    for row in rows {
        t.row(&row);
    }
    t.into_bytes()
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

/// `polbrdf map`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Material: a TOML file, or a preset name (see `polbrdf materials`).
    #[arg(long, value_name = "FILE.toml|PRESET")]
    pub material: String,
    #[command(flatten)]
    pub view: ViewArgs,
    /// Output directory (created if missing).
    #[arg(long, value_name = "DIR", default_value = "map-out")]
    pub out: PathBuf,
}

/// Runs `polbrdf map`.
pub fn run(args: &Args) -> Result<(), CliError> {
    let (light, grid) = args.view.build()?;
    let spectrum = args.view.spectral.spectrum()?;
    let (spec, name) = load_spec(&args.material, "--material")?;
    let nodes: Vec<(f64, Material)> =
        materials_at(&[(&spec, "--material", &args.material)], &spectrum)?
            .into_iter()
            .map(|(w, mut ms)| (w, ms.remove(0)))
            .collect();
    let samples = hemisphere_mean(&nodes, &light, &grid);
    let name = format!("{name}{}", describe(&spectrum));
    let files = map_files(&samples, &grid, &light, &name)?;
    let paths = write_all(&args.out, &files)?;
    let best = samples
        .iter()
        .filter(|s| s.stokes.0[0].is_finite())
        .max_by(|a, b| a.stokes.dolp().total_cmp(&b.stokes.dolp()));
    println!(
        "polbrdf map: {name}, sun at θi = {}°, φi = {}°, {} viewing directions ({}° × {}°)",
        short(args.view.sun_zenith_deg.unwrap_or(f64::NAN)),
        short(args.view.sun_azimuth_deg),
        grid.len(),
        short(deg(grid.theta_step())),
        short(deg(grid.phi_step()))
    );
    if let Some(b) = best {
        println!(
            "  highest DoLP {:.4} at θr = {:.1}°, φr = {:.1}°",
            b.stokes.dolp(),
            deg(b.theta_r),
            deg(b.phi_r)
        );
    }
    println!("Wrote {} files to {}", paths.len(), args.out.display());
    Ok(())
}

fn map_files(
    samples: &[ViewSample],
    grid: &ViewGrid,
    light: &Illumination,
    name: &str,
) -> Result<Vec<Output>, CliError> {
    let unpolarized = light.stokes() == Stokes::unpolarized();
    let s0: Vec<f64> = samples.iter().map(|s| s.stokes.0[0]).collect();
    let dolp: Vec<f64> = samples.iter().map(|s| s.stokes.dolp()).collect();
    let aolp: Vec<f64> = samples
        .iter()
        .map(|s| s.stokes.aolp().to_degrees())
        .collect();
    let marks = light_marks(light);
    let input = if unpolarized {
        String::new()
    } else {
        let s = light.stokes().0;
        format!(
            ", input S = ({}, {}, {}, {})",
            short(s[0]),
            short(s[1]),
            short(s[2]),
            short(s[3])
        )
    };
    let (lo, hi) = log_limits(&s0);
    let (brdf_title, brdf_label) = if unpolarized {
        (format!("BRDF — {name}"), "BRDF f = F₀₀ (sr⁻¹)")
    } else {
        (
            format!("Reflected S₀ — {name}{input}"),
            "S₀ per unit irradiance (sr⁻¹)",
        )
    };
    let brdf = PolarPanel {
        title: brdf_title,
        grid: polar_grid(grid, s0)?,
        scale: ColorScale::log10(Colormap::Viridis, lo, hi, brdf_label),
        marks: marks.clone(),
    };
    let dolp = PolarPanel {
        title: format!("DoLP — {name}{input}"),
        grid: polar_grid(grid, dolp)?,
        scale: dolp_scale(),
        marks: marks.clone(),
    };
    let aolp = PolarPanel {
        title: format!("AoLP — {name}{input}"),
        grid: polar_grid(grid, aolp)?,
        scale: angle_scale(Colormap::Cyclic, "AoLP (°, from s toward p)"),
        marks,
    };
    let mut files = vec![(
        "map.csv".to_string(),
        csv(
            &[
                "theta_r_deg",
                "phi_r_deg",
                "brdf",
                "s0",
                "s1",
                "s2",
                "s3",
                "dolp",
                "aolp_deg",
            ],
            samples.iter().map(|s| {
                let [s0, s1, s2, s3] = s.stokes.0;
                vec![
                    deg(s.theta_r),
                    deg(s.phi_r),
                    s.brdf,
                    s0,
                    s1,
                    s2,
                    s3,
                    s.stokes.dolp(),
                    s.stokes.aolp().to_degrees(),
                ]
            }),
        ),
    )];
    let overview = PolarFigure {
        panel_size: PANEL,
        columns: 3,
        panels: vec![brdf.clone(), dolp.clone(), aolp.clone()],
    };
    render_all(
        &mut files,
        &[
            ("brdf", single(brdf)),
            ("dolp", single(dolp)),
            ("aolp", single(aolp)),
            ("overview", overview),
        ],
    )?;
    Ok(files)
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
