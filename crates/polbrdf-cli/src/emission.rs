//! `polbrdf emission`: the emissivity Stokes vector of a material by Kirchhoff's law at a set of
//! view zenith angles (docs/model.md §16), one CSV row per angle with exactly the columns
//! `theta_deg, eps0, eps1, eps2, eps3, eps_s, eps_p, dolp, reciprocity_residual, valid`.

use crate::error::CliError;
use crate::output::write_output;
use crate::spectrum::{describe, load_spec, materials_at, SpectralArgs};
use polbrdf::analysis::emission::{emissivities, Emissivity};
use polbrdf::analysis::thermal::{planck, temperature};
use polbrdf::Stokes;
use polbrdf_io::csv_io::fmt_f64;
use polbrdf_io::CsvTable;
use std::path::PathBuf;

/// The columns of the emission table (a contract: other tools script against these names).
pub const COLUMNS: [&str; 10] = [
    "theta_deg",
    "eps0",
    "eps1",
    "eps2",
    "eps3",
    "eps_s",
    "eps_p",
    "dolp",
    "reciprocity_residual",
    "valid",
];

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
        allow_hyphen_values = true
    )]
    pub theta_deg: Vec<f64>,
    /// Output CSV (written atomically); standard output when absent.
    #[arg(long, value_name = "emission.csv")]
    pub output: Option<PathBuf>,
    /// Over a band, weight the wavelengths by Planck's law at this temperature (K) as well as
    /// by the response: the emissivity of a surface at that temperature, seen in the band.
    /// Without it, by the response only.
    #[arg(long, value_name = "K", requires = "band")]
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
    let angles: Vec<f64> = if args.theta_deg.is_empty() {
        (0..90).map(f64::from).collect()
    } else {
        args.theta_deg.clone()
    };
    crate::limits::at_most("--theta-deg (count)", angles.len(), crate::limits::ANGLES)?;
    if let Some(bad) = angles.iter().find(|t| !(**t >= 0.0 && **t < 90.0)) {
        return Err(CliError::Invalid(format!(
            "--theta-deg = {bad}: the view zenith angle must lie in [0, 90)"
        )));
    }
    if let Some(t) = args.temperature_k {
        temperature("--temperature-k", t).map_err(|e| CliError::Invalid(e.to_string()))?;
    }
    let spectrum = args.spectral.spectrum()?;
    let (spec, name) = load_spec(&args.material, "--material")?;
    let nodes = materials_at(&[(&spec, "--material", &args.material)], &spectrum)?;
    // The weights of the band mean: the response's, times B_λ(T) with --temperature-k.
    let weights: Vec<f64> = match args.temperature_k {
        Some(t) => {
            let w: Vec<f64> = nodes
                .iter()
                .map(|(w, ms)| w * planck(ms[0].wavelength_um().unwrap_or(1.0), t))
                .collect();
            let total: f64 = w.iter().sum();
            if total.is_nan() || total <= 0.0 {
                return Err(CliError::Invalid(format!(
                    "--temperature-k = {t}: Planck's law gives no radiance over the band"
                )));
            }
            w.iter().map(|x| x / total).collect()
        }
        None => nodes.iter().map(|(w, _)| *w).collect(),
    };
    let thetas: Vec<f64> = angles.iter().map(|t| t.to_radians()).collect();
    let zero = Stokes([0.0; 4]);
    let mut rows: Vec<(Emissivity, bool)> = thetas
        .iter()
        .map(|&t| {
            (
                Emissivity {
                    theta_r: t,
                    eps: zero,
                    eps_b: zero,
                },
                true,
            )
        })
        .collect();
    for ((_, ms), w) in nodes.iter().zip(&weights) {
        let at = emissivities(&ms[0], &thetas)
            .map_err(|e| CliError::Invalid(format!("--material {}: {e}", args.material)))?;
        for ((row, valid), e) in rows.iter_mut().zip(&at) {
            row.eps = row.eps.combine(1.0, &e.eps, *w);
            row.eps_b = row.eps_b.combine(1.0, &e.eps_b, *w);
            *valid &= e.is_valid();
        }
    }
    let mut table = CsvTable::new(COLUMNS);
    let mut invalid = Vec::new();
    for ((e, valid_nodes), deg) in rows.iter().zip(&angles) {
        let valid = *valid_nodes && e.is_valid();
        if !valid {
            invalid.push(*deg);
        }
        let [e0, e1, e2, e3] = e.eps.0;
        table.fields([
            fmt_f64(*deg),
            fmt_f64(e0),
            fmt_f64(e1),
            fmt_f64(e2),
            fmt_f64(e3),
            fmt_f64(e.eps_s()),
            fmt_f64(e.eps_p()),
            fmt_f64(e.dolp()),
            fmt_f64(e.reciprocity_residual()),
            valid.to_string(),
        ]);
    }
    write_output(args.output.as_deref(), &table.into_bytes())?;
    let what = format!("{name}{}", describe(&spectrum));
    if invalid.is_empty() {
        crate::note!(
            "polbrdf emission: {what}: {} view angle(s), every emissivity in [0, 1]",
            angles.len()
        );
    } else {
        crate::note!(
            "polbrdf emission: {what}: WARNING: at {} of {} view angle(s) ({}°) an emissivity \
             leaves [0, 1] — the parameter set reflects more than it receives there \
             (valid = false; values reported, not clipped)",
            invalid.len(),
            angles.len(),
            invalid
                .iter()
                .map(|d| d.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    Ok(())
}
