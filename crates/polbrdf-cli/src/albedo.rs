//! `polbrdf albedo`: the directional–hemispherical reflectance of a material at a set of
//! incidence angles, with every value above 1 (a parameter set that creates energy) flagged.

use crate::error::CliError;
use crate::spectrum::{describe, load_spec, materials_at, SpectralArgs};
use polbrdf::{directional_hemispherical, Albedo};
use polbrdf_io::csv_io::fmt_f64;
use polbrdf_io::CsvTable;
use std::path::PathBuf;

/// `polbrdf albedo`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Material: a TOML file, or a preset name (see `polbrdf materials`).
    #[arg(long, value_name = "FILE.toml|PRESET")]
    pub material: String,
    /// Incidence angle(s) in degrees, in [0, 90); repeat the option or separate with commas.
    /// Default: 0, 5, …, 85.
    #[arg(
        long,
        value_name = "DEG",
        value_delimiter = ',',
        allow_negative_numbers = true
    )]
    pub theta_i_deg: Vec<f64>,
    /// Also write the table as CSV (theta_i_deg, albedo, surface, volume, exceeds_one).
    #[arg(long, value_name = "albedo.csv")]
    pub output: Option<PathBuf>,
    #[command(flatten)]
    pub spectral: SpectralArgs,
}

/// Runs `polbrdf albedo`.
pub fn run(args: &Args) -> Result<(), CliError> {
    if let Some(out) = &args.output {
        let inputs = [std::path::Path::new(&args.material)];
        polbrdf_io::check_distinct(&inputs, &[out.as_path()])?;
    }
    let angles: Vec<f64> = if args.theta_i_deg.is_empty() {
        (0..18).map(|k| 5.0 * f64::from(k)).collect()
    } else {
        args.theta_i_deg.clone()
    };
    crate::limits::at_most("--theta-i-deg (count)", angles.len(), crate::limits::ANGLES)?;
    if let Some(bad) = angles.iter().find(|t| !(**t >= 0.0 && **t < 90.0)) {
        return Err(CliError::Invalid(format!(
            "--theta-i-deg = {bad}: the incidence angle must lie in [0, 90)"
        )));
    }
    let spectrum = args.spectral.spectrum()?;
    let (spec, name) = load_spec(&args.material, "--material")?;
    let nodes = materials_at(&[(&spec, "--material", &args.material)], &spectrum)?;
    let name = format!("{name}{}", describe(&spectrum));
    // Each albedo runs its quadrature nodes through the engine, in parallel; over a band, the
    // response-weighted mean of the albedos at the band's nodes.
    let rows: Vec<Albedo> = angles
        .iter()
        .map(|t| {
            let mut a = Albedo {
                theta_i: t.to_radians(),
                surface: 0.0,
                volume: 0.0,
            };
            for (w, ms) in &nodes {
                let x = directional_hemispherical(&ms[0], t.to_radians());
                a.surface += w * x.surface;
                a.volume += w * x.volume;
            }
            a
        })
        .collect();

    if let Some(path) = &args.output {
        let mut t = CsvTable::new(["theta_i_deg", "albedo", "surface", "volume", "exceeds_one"]);
        for (theta, a) in angles.iter().zip(&rows) {
            t.fields([
                fmt_f64(*theta),
                fmt_f64(a.total()),
                fmt_f64(a.surface),
                fmt_f64(a.volume),
                (a.total() > 1.0).to_string(),
            ]);
        }
        polbrdf_io::write_atomic(path, &t.into_bytes())?;
    }

    let mut out = format!(
        "polbrdf albedo: directional–hemispherical reflectance of {name}\n\
         ρ(θi) = ∫ f(θi; θr, φr) cosθr dΩr over the viewing hemisphere; above 1 the parameters \
         create energy\n\n  {:>7} {:>10} {:>10} {:>10}\n",
        "θi (°)", "albedo", "surface", "volume"
    );
    for (t, a) in angles.iter().zip(&rows) {
        out += &format!(
            "  {:>7} {:>10.6} {:>10.6} {:>10.6}",
            fmt_angle(*t),
            a.total(),
            a.surface,
            a.volume
        );
        if a.total().is_infinite() {
            out += "   <-- DIVERGES (infinite)";
        } else if a.total() > 1.0 {
            out += &format!(
                "   <-- EXCEEDS 1 by {:.4} ({:.1} %)",
                a.total() - 1.0,
                100.0 * (a.total() - 1.0)
            );
        }
        out.push('\n');
    }
    let over: Vec<(f64, f64)> = angles
        .iter()
        .zip(&rows)
        .filter(|(_, a)| a.total() > 1.0)
        .map(|(t, a)| (*t, a.total()))
        .collect();
    out.push('\n');
    if over.iter().any(|(_, v)| v.is_infinite()) {
        out += &format!(
            "WARNING: the albedo is infinite at {} of {} incidence angles: with the paper form's \
             surface term cos²θN/(4cos²θi cos²θr), f·cosθr grows like 1/cosθr toward the \
             horizon and its integral diverges (docs/model.md §10); use form = \"standard\" \
             for albedo, emission and sky integrals.\n",
            over.iter().filter(|(_, v)| v.is_infinite()).count(),
            rows.len(),
        );
    } else if let Some(&(t, v)) = over.iter().max_by(|a, b| a.1.total_cmp(&b.1)) {
        out += &format!(
            "WARNING: the albedo exceeds 1 at {} of {} incidence angles (largest {:.4} at θi = {}°): \
             this parameter set violates energy conservation there.\n",
            over.len(),
            rows.len(),
            v,
            fmt_angle(t)
        );
    } else {
        let max = rows.iter().map(Albedo::total).fold(0.0, f64::max);
        out += &format!(
            "The albedo stays at or below 1 at every incidence angle given (largest {max:.4}): \
             energy is conserved there.\n"
        );
    }
    print!("{out}");
    Ok(())
}

fn fmt_angle(t: f64) -> String {
    if t == t.round() {
        format!("{t:.1}")
    } else {
        fmt_f64(t)
    }
}
