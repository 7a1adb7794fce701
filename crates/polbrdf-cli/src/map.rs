//! `polbrdf map`: hemispherical maps (polar plots) of the BRDF, DoLP and AoLP of one material
//! for a given illumination — the task layer's [`hemisphere`], rendered.

use crate::error::CliError;
use crate::figures::{
    angle_scale, dolp_scale, input_stokes, invalid_marks, light_marks, log_limits, polar_grid,
    render_all, short, single, INVALID_LEGEND, PANEL,
};
use crate::output::{csv, write_all, OutputFile};
use crate::view::ViewArgs;
use polbrdf::Stokes;
use polbrdf_plot::{ColorScale, Colormap, PolarFigure, PolarPanel};
use polbrdf_tasks::hemisphere::{deg, hemisphere, Hemisphere, HemisphereRequest};
use polbrdf_tasks::spectrum::describe;
use std::path::PathBuf;

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
    let request = HemisphereRequest {
        material: args.material.clone(),
        light: args.view.light()?,
        grid_deg: args.view.grid_deg(),
        spectral: args.view.spectral.request(),
    };
    let map = hemisphere(&request)?;
    let name = format!("{}{}", map.material.name, describe(map.spectrum.as_ref()));
    let files = map_files(&map, &name)?;
    let paths = write_all(&args.out, &files)?;
    crate::note!(
        "polbrdf map: {name}, sun at θi = {}°, φi = {}°, {} viewing directions ({}° × {}°)",
        short(args.view.sun_zenith_deg.unwrap_or(f64::NAN)),
        short(args.view.sun_azimuth_deg),
        map.grid.len(),
        short(deg(map.grid.theta_step())),
        short(deg(map.grid.phi_step()))
    );
    if let Some(b) = map.highest_dolp() {
        crate::note!(
            "  highest DoLP {:.4} at θr = {:.1}°, φr = {:.1}°",
            b.stokes.dolp(),
            deg(b.theta_r),
            deg(b.phi_r)
        );
    }
    if let Some(t) = map.invalid_zeniths.first() {
        crate::note!(
            "  model flagged invalid (emissivity outside [0, 1]) at {} zenith(s) from θr = {}° \
             (marked on the maps)",
            map.invalid_zeniths.len(),
            short(deg(*t))
        );
    }
    crate::note!("Wrote {} files to {}", paths.len(), args.out.display());
    Ok(())
}

fn map_files(map: &Hemisphere, name: &str) -> Result<Vec<OutputFile>, CliError> {
    let (samples, grid, light) = (&map.samples, &map.grid, &map.light);
    let unpolarized = light.stokes() == Stokes::unpolarized();
    let s0: Vec<f64> = samples.iter().map(|s| s.stokes.0[0]).collect();
    let dolp: Vec<f64> = samples.iter().map(|s| s.stokes.dolp()).collect();
    let aolp: Vec<f64> = samples
        .iter()
        .map(|s| s.stokes.aolp().to_degrees())
        .collect();
    let mut marks = light_marks(light);
    marks.extend(invalid_marks(&map.invalid_zeniths, INVALID_LEGEND));
    let input = input_stokes(light, (", input S = (", ")"));
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
    let mut files = vec![("map.csv".to_string(), csv(&Hemisphere::COLUMNS, map.rows()))];
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
