//! `polbrdf radiance`: the observed Stokes radiance of a surface in a scene (docs/model.md §17)
//! at a set of view directions — its thermal emission, the sky it reflects and the atmosphere.
//! Columns: `theta_r_deg, phi_r_deg, s0, s1, s2, s3, dolp, aolp_deg` (a contract: other tools
//! and later commands build on it).

use crate::error::CliError;
use crate::output::write_output;
use crate::spectrum::{describe, load_spec};
use polbrdf::analysis::scene::Observer;
use polbrdf_io::CsvTable;
use std::path::PathBuf;

/// The columns of the radiance table.
pub const COLUMNS: [&str; 8] = [
    "theta_r_deg",
    "phi_r_deg",
    "s0",
    "s1",
    "s2",
    "s3",
    "dolp",
    "aolp_deg",
];

/// `polbrdf radiance`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Material: a TOML file, or a preset name (see `polbrdf materials`).
    #[arg(long, value_name = "FILE.toml|PRESET")]
    pub material: String,
    /// The scene: wavelength or band, the surface temperature, sky and atmosphere (TOML; see
    /// the README).
    #[arg(long, value_name = "SCENE.toml")]
    pub scene: PathBuf,
    /// View zenith angle(s) in degrees, in [0, 90); with --phi-deg, every combination.
    /// Default: 0, 5, …, 85.
    #[arg(
        long,
        value_name = "DEG",
        value_delimiter = ',',
        allow_hyphen_values = true,
        conflicts_with = "input"
    )]
    pub theta_deg: Vec<f64>,
    /// View azimuth(s) in degrees. Default: 0.
    #[arg(
        long,
        value_name = "DEG",
        value_delimiter = ',',
        allow_hyphen_values = true,
        conflicts_with = "input"
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

/// An error of [`Observer::new`] for the material `what` names. Over a band, a wavelength
/// outside the material's data is one of the quadrature's nodes: the message names the band.
pub(crate) fn observer_error(
    what: &str,
    e: &polbrdf::Error,
    spectrum: &polbrdf::Spectrum,
) -> CliError {
    if let (
        polbrdf::Spectrum::Band(band, _),
        polbrdf::Error::WavelengthOutOfRange {
            material, range, ..
        },
    ) = (spectrum, e)
    {
        let (lo, hi) = band.range();
        return CliError::Invalid(format!(
            "{what}: the band {} ({lo}–{hi} µm) reaches outside the data of `{material}` \
             ({} – {} µm)",
            band.name(),
            range.0,
            range.1
        ));
    }
    CliError::Invalid(format!("{what}: {e}"))
}

/// Runs `polbrdf radiance`.
pub fn run(args: &Args) -> Result<(), CliError> {
    if let Some(out) = &args.output {
        let mut inputs = vec![std::path::Path::new(&args.material), args.scene.as_path()];
        inputs.extend(args.input.as_deref());
        polbrdf_io::check_distinct(&inputs, &[out.as_path()])?;
    }
    let views: Vec<(f64, f64)> = match &args.input {
        Some(path) => polbrdf_io::read_views_csv(path)?,
        None => {
            let thetas: Vec<f64> = if args.theta_deg.is_empty() {
                (0..18).map(|k| 5.0 * f64::from(k)).collect()
            } else {
                args.theta_deg.clone()
            };
            let phis = if args.phi_deg.is_empty() {
                vec![0.0]
            } else {
                args.phi_deg.clone()
            };
            if let Some(bad) = thetas.iter().find(|t| !(**t >= 0.0 && **t < 90.0)) {
                return Err(CliError::Invalid(format!(
                    "--theta-deg = {bad}: the view zenith angle must lie in [0, 90)"
                )));
            }
            if let Some(bad) = phis.iter().find(|p| !p.is_finite()) {
                return Err(CliError::Invalid(format!(
                    "--phi-deg = {bad}: must be finite"
                )));
            }
            crate::limits::product_at_most(
                "--theta-deg × --phi-deg",
                thetas.len(),
                phis.len(),
                crate::limits::ANGLES,
            )?;
            thetas
                .iter()
                .flat_map(|t| phis.iter().map(move |p| (*t, *p)))
                .collect()
        }
    };
    let scene = polbrdf_io::read_scene(&args.scene)?;
    let (spec, name) = load_spec(&args.material, "--material")?;
    let observer = Observer::new(&spec, &scene.thermal, &scene.spectrum).map_err(|e| {
        observer_error(
            &format!("--material {}", args.material),
            &e,
            &scene.spectrum,
        )
    })?;
    let radians: Vec<(f64, f64)> = views
        .iter()
        .map(|(t, p)| (t.to_radians(), p.to_radians()))
        .collect();
    let observed = observer.observe(&radians);
    let mut table = CsvTable::new(COLUMNS);
    for ((t, p), r) in views.iter().zip(&observed) {
        let s = r.stokes;
        table.row(&[
            *t,
            *p,
            s.0[0],
            s.0[1],
            s.0[2],
            s.0[3],
            s.dolp(),
            s.aolp().to_degrees(),
        ]);
    }
    write_output(args.output.as_deref(), &table.into_bytes())?;
    let unit = match scene.spectrum {
        polbrdf::Spectrum::Wavelength(_) => "W·m⁻²·sr⁻¹·µm⁻¹",
        polbrdf::Spectrum::Band(..) => "W·m⁻²·sr⁻¹ (band-integrated)",
    };
    crate::note!(
        "polbrdf radiance: {name}{} in {}: {} view(s); Stokes radiance in {unit}",
        describe(&Some(scene.spectrum.clone())),
        scene.path.display(),
        views.len()
    );
    Ok(())
}
