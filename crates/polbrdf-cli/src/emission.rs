//! `polbrdf emission`: the emissivity Stokes vector of a material by Kirchhoff's law at a set of
//! view zenith angles (docs/model.md §16), one CSV row per angle with exactly the columns
//! `theta_deg, eps0, eps1, eps2, eps3, eps_s, eps_p, dolp, reciprocity_residual, valid`.

use crate::error::CliError;
use crate::output::write_output;
use crate::spectrum::SpectralArgs;
use polbrdf_io::csv_io::fmt_f64;
use polbrdf_io::CsvTable;
use polbrdf_tasks::emission::{emission, EmissionRequest, EmissionTable};
use std::path::PathBuf;

/// `polbrdf emission`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Material: a TOML file, or a preset name (see `polbrdf materials`).
    #[arg(long, value_name = "FILE.toml|PRESET")]
    pub material: String,
    /// View zenith angle(s) in degrees, in [0, 90); repeat the option or separate with commas.
    /// Default: 0, 1, …, 89.
    #[arg(
        long,
        value_name = "DEG",
        value_delimiter = ',',
        allow_hyphen_values = true,
        value_parser = crate::values::zenith()
    )]
    pub theta_deg: Vec<f64>,
    /// Output CSV (written atomically); standard output when absent.
    #[arg(long, value_name = "emission.csv")]
    pub output: Option<PathBuf>,
    /// Over a band, weight the wavelengths by Planck's law at this temperature (K) as well as
    /// by the response: the emissivity of a surface at that temperature, seen in the band.
    /// Without it, by the response only.
    #[arg(long, value_name = "K", requires = "band", value_parser = crate::values::positive())]
    pub temperature_k: Option<f64>,
    #[command(flatten)]
    pub spectral: SpectralArgs,
}

/// Runs `polbrdf emission`.
pub fn run(args: &Args) -> Result<(), CliError> {
    if let Some(out) = &args.output {
        let inputs = [std::path::Path::new(&args.material)];
        polbrdf_io::check_distinct(&inputs, &[out.as_path()])?;
    }
    let table = emission(&EmissionRequest {
        material: args.material.clone(),
        theta_deg: args.theta_deg.clone(),
        temperature_k: args.temperature_k,
        spectral: args.spectral.request(),
    })?;
    let mut csv = CsvTable::new(EmissionTable::COLUMNS);
    for row in &table.rows {
        let e = &row.emissivity;
        let [e0, e1, e2, e3] = e.eps.0;
        csv.fields([
            fmt_f64(row.theta_deg),
            fmt_f64(e0),
            fmt_f64(e1),
            fmt_f64(e2),
            fmt_f64(e3),
            fmt_f64(e.eps_s()),
            fmt_f64(e.eps_p()),
            fmt_f64(e.dolp()),
            fmt_f64(e.reciprocity_residual()),
            row.valid.to_string(),
        ]);
    }
    write_output(args.output.as_deref(), &csv.into_bytes())?;
    let what = table.title();
    let invalid = table.invalid_angles();
    if invalid.is_empty() {
        crate::note!(
            "polbrdf emission: {what}: {} view angle(s), every emissivity in [0, 1]",
            table.rows.len()
        );
    } else {
        crate::note!(
            "polbrdf emission: {what}: WARNING: at {} of {} view angle(s) ({}°) an emissivity \
             leaves [0, 1] — the parameter set reflects more than it receives there \
             (valid = false; values reported, not clipped)",
            invalid.len(),
            table.rows.len(),
            invalid
                .iter()
                .map(|d| d.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    Ok(())
}
