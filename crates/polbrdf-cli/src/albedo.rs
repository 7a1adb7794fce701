//! `polbrdf albedo`: the directional–hemispherical reflectance of a material at a set of
//! incidence angles, with every value above 1 (a parameter set that creates energy) flagged.

use crate::error::CliError;
use crate::output::write_output;
use crate::spectrum::SpectralArgs;
use polbrdf_io::csv_io::fmt_f64;
use polbrdf_io::CsvTable;
use polbrdf_tasks::albedo::{albedo, AlbedoRequest, AlbedoTable, Verdict};
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
        allow_negative_numbers = true,
        value_parser = crate::values::zenith()
    )]
    pub theta_i_deg: Vec<f64>,
    /// The table as CSV (theta_i_deg, albedo, surface, volume, exceeds_one), written
    /// atomically; standard output when absent or `-` (the human table goes to standard error).
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
    let table = albedo(&AlbedoRequest {
        material: args.material.clone(),
        theta_i_deg: args.theta_i_deg.clone(),
        spectral: args.spectral.request(),
    })?;
    let mut t = CsvTable::new(AlbedoTable::COLUMNS);
    for (theta, a) in &table.rows {
        t.fields([
            fmt_f64(*theta),
            fmt_f64(a.total()),
            fmt_f64(a.surface),
            fmt_f64(a.volume),
            (a.total() > 1.0).to_string(),
        ]);
    }
    write_output(args.output.as_deref(), &t.into_bytes())?;
    crate::output::note(&summary(&table));
    Ok(())
}

/// The table and the verdict, for a person: on standard error.
fn summary(table: &AlbedoTable) -> String {
    let mut out = format!(
        "polbrdf albedo: directional–hemispherical reflectance of {}\n\
         ρ(θi) = ∫ f(θi; θr, φr) cosθr dΩr over the viewing hemisphere; above 1 the parameters \
         create energy\n\n  {:>7} {:>10} {:>10} {:>10}\n",
        table.title(),
        "θi (°)",
        "albedo",
        "surface",
        "volume"
    );
    for (t, a) in &table.rows {
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
    out.push('\n');
    let n = table.rows.len();
    out += &match table.verdict() {
        Verdict::Diverges { count } => format!(
            "WARNING: the albedo is infinite at {count} of {n} incidence angles: with the paper \
             form's surface term cos²θN/(4cos²θi cos²θr), f·cosθr grows like 1/cosθr toward the \
             horizon and its integral diverges (docs/model.md §10); use form = \"standard\" \
             for albedo, emission and sky integrals.\n"
        ),
        Verdict::Exceeds {
            count,
            largest,
            theta_i_deg,
        } => format!(
            "WARNING: the albedo exceeds 1 at {count} of {n} incidence angles (largest \
             {largest:.4} at θi = {}°): this parameter set violates energy conservation there.\n",
            fmt_angle(theta_i_deg)
        ),
        Verdict::Conserves { largest } => format!(
            "The albedo stays at or below 1 at every incidence angle given (largest \
             {largest:.4}): energy is conserved there.\n"
        ),
    };
    out
}

fn fmt_angle(t: f64) -> String {
    if t == t.round() {
        format!("{t:.1}")
    } else {
        fmt_f64(t)
    }
}
