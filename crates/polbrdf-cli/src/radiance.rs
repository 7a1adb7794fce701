//! `polbrdf radiance`: the observed Stokes radiance of a surface in a scene (docs/model.md §17)
//! at a set of view directions — its thermal emission, the sky it reflects and the atmosphere.
//! Columns: `theta_r_deg, phi_r_deg, s0, s1, s2, s3, dolp, aolp_deg` (a contract: other tools
//! and later commands build on it).

use crate::error::CliError;
use crate::output::write_output;
use polbrdf_io::CsvTable;
use polbrdf_tasks::radiance::{radiance, RadianceRequest, RadianceTable, Views, VIEWS_FIELD};
use polbrdf_tasks::spectrum::describe;
use polbrdf_tasks::TaskError;
use std::path::PathBuf;

/// `polbrdf radiance`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Material: a TOML file, or a preset name (see `polbrdf materials`).
    #[arg(long, value_name = "FILE.toml|PRESET")]
    pub material: String,
    /// The scene: wavelength or band, the surface temperature, sky and atmosphere (TOML; see
    /// docs/guide-emission.md).
    #[arg(long, value_name = "SCENE.toml")]
    pub scene: PathBuf,
    /// View zenith angle(s) in degrees, in [0, 90); with --phi-deg, every combination.
    /// Default: 0, 5, …, 85.
    #[arg(
        long,
        value_name = "DEG",
        value_delimiter = ',',
        allow_hyphen_values = true,
        conflicts_with = "input",
        value_parser = crate::values::zenith()
    )]
    pub theta_deg: Vec<f64>,
    /// View azimuth(s) in degrees. Default: 0.
    #[arg(
        long,
        value_name = "DEG",
        value_delimiter = ',',
        allow_hyphen_values = true,
        conflicts_with = "input",
        value_parser = crate::values::azimuth()
    )]
    pub phi_deg: Vec<f64>,
    /// A CSV of view directions (columns theta_r_deg, phi_r_deg; other columns are ignored)
    /// instead of --theta-deg/--phi-deg.
    #[arg(long, value_name = "views.csv")]
    pub input: Option<PathBuf>,
    /// Output CSV (written atomically); standard output when absent.
    #[arg(long, value_name = "radiance.csv")]
    pub output: Option<PathBuf>,
}

/// Runs `polbrdf radiance`.
pub fn run(args: &Args) -> Result<(), CliError> {
    if let Some(out) = &args.output {
        let mut inputs = vec![std::path::Path::new(&args.material), args.scene.as_path()];
        inputs.extend(args.input.as_deref());
        polbrdf_io::check_distinct(&inputs, &[out.as_path()])?;
    }
    let views = match &args.input {
        Some(path) => Views::List(polbrdf_io::read_views_csv(path)?),
        None => {
            let (thetas, phis) = Views::grid_axes(&args.theta_deg, &args.phi_deg)?;
            crate::limits::product_at_most(
                "--theta-deg × --phi-deg",
                thetas.len(),
                phis.len(),
                crate::limits::ANGLES,
            )?;
            Views::Grid {
                theta_deg: thetas,
                phi_deg: phis,
            }
        }
    };
    let table = radiance(&RadianceRequest {
        material: args.material.clone(),
        scene: args.scene.clone(),
        views,
    })
    .map_err(|e| match e {
        TaskError::Usage { field, message } if field == VIEWS_FIELD => {
            CliError::Usage(format!("--theta-deg × --phi-deg (or --input): {message}"))
        }
        e => e.into(),
    })?;
    let mut csv = CsvTable::new(RadianceTable::COLUMNS);
    for row in table.values() {
        csv.row(&row);
    }
    write_output(args.output.as_deref(), &csv.into_bytes())?;
    let unit = match table.scene.spectrum {
        polbrdf::Spectrum::Wavelength(_) => "W·m⁻²·sr⁻¹·µm⁻¹",
        polbrdf::Spectrum::Band(..) => "W·m⁻²·sr⁻¹ (band-integrated)",
    };
    crate::note!(
        "polbrdf radiance: {}{} in {}: {} view(s); Stokes radiance in {unit}",
        table.material.name,
        describe(Some(&table.scene.spectrum)),
        table.scene.path.display(),
        table.rows.len()
    );
    Ok(())
}
