//! `polbrdf fit`: material parameters from measurements, with uncertainties.

use crate::error::CliError;
use crate::output::write_output;
use polbrdf_fit::{
    fit, fit_per_wavelength, Bound, FitOptions, FitResult, Measurement, Param, WavelengthFit,
};
use serde_json::{json, Value};
use std::path::Path;

/// What `polbrdf fit` was asked to do.
pub struct Args<'a> {
    pub material: &'a str,
    pub data: &'a Path,
    pub free: &'a str,
    pub output: Option<&'a Path>,
    pub material_out: Option<&'a Path>,
    pub starts: usize,
    pub seed: u64,
    pub plot: Option<&'a Path>,
    pub per_wavelength: bool,
    pub index_out: Option<&'a Path>,
    /// `.pbsdf` tables: keep every n-th node along each axis (`None`: automatic).
    pub subsample: Option<usize>,
    /// `.pbsdf` tables: leave out the cells whose matrix is not physically realizable.
    pub exclude_inadmissible: bool,
}

/// Runs `polbrdf fit` on a measurement CSV (`main` sends a `.pbsdf` table to
/// the `.pbsdf` fit of `measured.rs`; the output layer's checks of the paths ran before).
pub fn run(args: &Args<'_>) -> Result<(), CliError> {
    // Options before data (issue 35): no file is read for a command line that is refused.
    // --free names the parameters: a bad name is a usage error (exit 2).
    let free = Param::parse_list(args.free).map_err(|e| CliError::Usage(format!("--free: {e}")))?;
    let base = crate::output::load_material(args.material)?;
    let table = polbrdf_io::read_measurements_csv(args.data)?;
    let mut scan = polbrdf_io::AngleScan::default();
    table.geometries.iter().for_each(|g| scan.add(g));
    crate::output::unit_warnings(scan.warning(&args.data.display().to_string()).as_slice());
    let data = polbrdf_tasks::fit::measurements(&table)?;
    drop(table);
    let opts = FitOptions {
        extra_starts: args.starts,
        seed: args.seed,
        ..FitOptions::default()
    };
    if args.per_wavelength {
        return run_per_wavelength(args, &base, &free, &data, &opts);
    }
    let result = fit(&base, &free, &data, &opts)?;

    let json = serde_json::to_string_pretty(&polbrdf_tasks::fit::to_json(&result, args.data))
        .expect("JSON of finite and null values");
    // Files first, standard output next, the summary (standard error) last: a closed pipe
    // never costs a file, and a file that failed is never hidden by a summary.
    if let Some(path) = args.output {
        polbrdf_io::write_atomic(path, (json.clone() + "\n").as_bytes())?;
    }
    if let Some(path) = args.plot {
        crate::residuals::write_plot(path, &result, &data)?;
    }
    if let Some(path) = args.material_out {
        let mut spec = result.spec.clone();
        spec.name = Some(format!(
            "{} (fitted to {})",
            base.name.as_deref().unwrap_or("material"),
            args.data.display()
        ));
        polbrdf_io::write_atomic(path, polbrdf_io::material_to_toml(&spec).as_bytes())?;
    }
    if args.output.is_none() {
        write_output(None, (json + "\n").as_bytes())?;
    }
    crate::output::note(&summary(&result, args.data, data.len()));
    if !result.converged {
        return Err(CliError::NotConverged(result.message));
    }
    Ok(())
}

/// The one-screen summary printed on the terminal.
fn summary(r: &FitResult, data: &Path, n: usize) -> String {
    let mut s = summary_heading(r, data, n);
    s += &parameter_table(r);
    s += &correlation_table(r);
    s += &zero_bistatic_line(r);
    s
}

/// The summary's heading: the data, whether the fit converged, χ² and the fit's warnings.
fn summary_heading(r: &FitResult, data: &Path, n: usize) -> String {
    let mut s = format!(
        "polbrdf fit: {} measurement(s) from {}, {} free parameter(s)\n",
        n,
        data.display(),
        r.params.len()
    );
    s += &format!(
        "  {}: {} after {} iterations; {} of {} start(s) reached the best χ²\n",
        if r.converged {
            "converged"
        } else {
            "NOT CONVERGED"
        },
        r.message,
        r.iterations,
        r.starts.1,
        r.starts.0
    );
    s += &format!(
        "  χ² = {:.6e}, dof = {}, χ²/dof = {:.4}{}\n\n",
        r.chi2,
        r.dof,
        r.reduced_chi2,
        if r.scaled_by_residuals {
            " (no σ given for some values: uncertainties scaled by χ²/dof)"
        } else {
            ""
        }
    );
    for w in &r.warnings {
        s += &format!("  warning: {w}\n");
    }
    s
}

/// One row per free parameter (value, standard error, relative error; or the 95 % upper limit
/// of one at its lower bound), then a note on each parameter at its bound.
fn parameter_table(r: &FitResult) -> String {
    let mut s = format!(
        "  {:<10} {:>16} {:>14} {:>10}\n",
        "parameter", "value", "std. error", "rel."
    );
    let mut notes = String::new();
    for (k, p) in r.params.iter().enumerate() {
        match &r.bounds[k] {
            Bound::Interior => {
                s += &format!(
                    "  {:<10} {:>16.8e} {:>14.3e} {:>9.2}%\n",
                    p.name(),
                    r.values[k],
                    r.stderr[k],
                    100.0 * r.stderr[k] / r.values[k].abs().max(f64::MIN_POSITIVE)
                );
            }
            Bound::AtLowerBound {
                upper_limit_95,
                correlation_at_limit,
            } => {
                let limit =
                    upper_limit_95.map_or("unbounded".to_string(), |u| format!("< {u:.3e}"));
                s += &format!(
                    "  {:<10} {:>16} {:>14}   (at its lower bound; 95 % upper limit)\n",
                    p.name(),
                    format!("{:.1}", r.values[k]),
                    limit
                );
                notes += &lower_bound_note(r, k, correlation_at_limit.as_deref());
            }
        }
    }
    s + &notes
}

/// The note on parameter `k` at its lower bound: what its upper limit means, and (given its
/// correlations at that limit) the parameter it trades off against most.
fn lower_bound_note(r: &FitResult, k: usize, correlation_at_limit: Option<&[f64]>) -> String {
    let p = &r.params[k];
    let mut note = format!(
        "\n  `{}` ends at its lower bound {}: the data prefer no larger value. The one-sided \
         95 % upper limit is where the best χ² over the other parameters rises by 2.706{}.",
        p.name(),
        r.values[k],
        if r.scaled_by_residuals {
            " × χ²/dof"
        } else {
            ""
        }
    );
    if let Some(c) = correlation_at_limit {
        let strongest = r
            .params
            .iter()
            .zip(c)
            .enumerate()
            .filter(|(j, _)| *j != k)
            .max_by(|a, b| a.1 .1.abs().total_cmp(&b.1 .1.abs()));
        if let Some((_, (q, v))) = strongest {
            note += &format!(
                " At that limit it is correlated {v:+.3} with `{}`: what it trades off against.",
                q.name()
            );
        }
    }
    note + "\n"
}

/// The correlation matrix of the free parameters (none for a single one).
fn correlation_table(r: &FitResult) -> String {
    let mut s = String::new();
    if r.params.len() > 1 {
        s += "\n  correlation:\n";
        for (k, p) in r.params.iter().enumerate() {
            s += &format!("  {:<10}", p.name());
            for c in &r.correlation[k] {
                s += &format!(" {c:>7.3}");
            }
            s += "\n";
        }
    }
    s
}

/// The zero-bistatic start's line (eq. 5), when the fit made one.
fn zero_bistatic_line(r: &FitResult) -> String {
    r.zero_bistatic.as_ref().map_or_else(String::new, |z| {
        format!(
            "\n  zero-bistatic start (eq. 5 with the start values of n, k, ρ_D, ρ_V): a = {:.4} ± {:.2e} sr⁻¹,\n    b = {:.4} ± {:.2e} rad⁻² ({} backscatter points{})\n",
            z.a,
            z.stderr_a,
            z.b,
            z.stderr_b,
            z.samples.len(),
            if z.excluded.is_empty() {
                String::new()
            } else {
                format!(", {} excluded: within noise of the volume term", z.excluded.len())
            }
        )
    })
}

/// `polbrdf fit --per-wavelength`: one fit per wavelength of the data.
fn run_per_wavelength(
    args: &Args<'_>,
    base: &polbrdf::MaterialSpec,
    free: &[Param],
    data: &[Measurement],
    opts: &FitOptions,
) -> Result<(), CliError> {
    let fits = fit_per_wavelength(base, free, data, opts)?;
    let s = per_wavelength_summary(args.data, data.len(), free, &fits);
    let json = serde_json::to_string_pretty(&per_wavelength_json(args.data, free, &fits))
        .expect("JSON of finite and null values");
    // Files first, then standard output, then the summary (as `run`).
    if let Some(path) = args.output {
        polbrdf_io::write_atomic(path, (json.clone() + "\n").as_bytes())?;
    }
    if let Some(path) = args.index_out {
        polbrdf_io::write_atomic(path, index_file(args.data, free, &fits)?.as_bytes())?;
    }
    if args.output.is_none() {
        write_output(None, (json + "\n").as_bytes())?;
    }
    crate::output::note(&s);
    let failed: Vec<f64> = fits
        .iter()
        .filter(|f| f.result.is_err())
        .map(|f| f.wavelength_um)
        .collect();
    if failed.is_empty() {
        Ok(())
    } else {
        Err(CliError::Invalid(format!(
            "the fit was refused at {} wavelength(s) ({} µm); the others were written",
            failed.len(),
            failed
                .iter()
                .map(|l| l.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        )))
    }
}

/// The per-wavelength summary: one row per wavelength with each free parameter (value ± standard
/// error, or the upper limit of one at its bound) and χ²/dof, or why the fit was refused.
fn per_wavelength_summary(data: &Path, n: usize, free: &[Param], fits: &[WavelengthFit]) -> String {
    let mut s = format!(
        "polbrdf fit --per-wavelength: {} measurement(s) from {} at {} wavelength(s), {} free \
         parameter(s)\n\n  {:>10}",
        n,
        data.display(),
        fits.len(),
        free.len(),
        "λ (µm)"
    );
    for p in free {
        s += &format!(" {:>24}", p.name());
    }
    s += "   χ²/dof\n";
    for f in fits {
        s += &format!("  {:>10.4}", f.wavelength_um);
        match &f.result {
            Ok(r) => {
                for (k, _) in free.iter().enumerate() {
                    s += &match &r.bounds[k] {
                        Bound::Interior => {
                            format!(" {:>12.6} ± {:<9.2e}", r.values[k], r.stderr[k])
                        }
                        Bound::AtLowerBound { upper_limit_95, .. } => format!(
                            " {:>12} < {:<9.2e}",
                            "0 (bound)",
                            upper_limit_95.unwrap_or(f64::INFINITY)
                        ),
                    };
                }
                s += &format!(
                    "   {:.3}{}\n",
                    r.reduced_chi2,
                    if r.converged { "" } else { "  NOT CONVERGED" }
                );
            }
            Err(e) => s += &format!("   refused: {e}\n"),
        }
    }
    s
}

/// The per-wavelength fit document: each wavelength's fit (as `fit.json`, with its
/// wavelength) or why it was refused, the parameter order and the data file.
fn per_wavelength_json(data: &Path, free: &[Param], fits: &[WavelengthFit]) -> Value {
    let entries: Vec<Value> = fits
        .iter()
        .map(|f| match &f.result {
            Ok(r) => {
                let mut v = polbrdf_tasks::fit::to_json(r, data);
                v["wavelength_um"] = Value::from(f.wavelength_um);
                v
            }
            Err(e) => json!({"wavelength_um": f.wavelength_um, "refused": e.to_string()}),
        })
        .collect();
    json!({
        "per_wavelength": entries,
        "parameter_order": free.iter().map(|p| p.name()).collect::<Vec<_>>(),
        "data": data.display().to_string(),
    })
}

/// The `--index-out` file: the fitted effective index (n, and k where it is free, else the
/// base material's) per wavelength that was fitted, as a refractiveindex.info YAML table.
fn index_file(data: &Path, free: &[Param], fits: &[WavelengthFit]) -> Result<String, CliError> {
    let n_at = free.iter().position(|p| *p == Param::N).ok_or_else(|| {
        CliError::Invalid("--index-out needs `n` among the free parameters".into())
    })?;
    let k_at = free.iter().position(|p| *p == Param::K);
    let mut text = format!(
        "# Effective index fitted by `polbrdf fit --per-wavelength` to {}\n\
         REFERENCES: |\n    Fitted with polbrdf to {}\nCOMMENTS: |\n    n, k per wavelength; \
         the fit's standard errors are in its fit.json\nDATA:\n  - type: tabulated nk\n    data: |\n",
        data.display(),
        data.display()
    );
    for f in fits {
        if let Ok(r) = &f.result {
            let k = k_at.map_or(r.spec.k, |j| r.values[j]);
            text += &format!("        {} {} {}\n", f.wavelength_um, r.values[n_at], k);
        }
    }
    Ok(text)
}
