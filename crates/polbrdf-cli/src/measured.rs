//! `polbrdf fit --data table.pbsdf`: the fit of a measured Mitsuba 3 table (docs/model.md §20),
//! one band at a time, on a subsampled grid, by the task layer (`polbrdf_tasks::pbsdf`): this
//! module validates the options, checks every output name, and renders.

use crate::error::CliError;
use crate::fit::Args;
use crate::output::write_output;
use polbrdf_fit::{FitOptions, Param};
use polbrdf_io::PbsdfTable;
use polbrdf_tasks::pbsdf::{fit_table, plan, BandFit};
use std::path::{Path, PathBuf};

/// The residual plot of the band at `nm`: `P_<nm>nm.<ext>` next to `--plot P`.
pub fn band_path(path: &Path, nm: u16) -> PathBuf {
    let stem = path
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("residuals");
    let ext = path.extension().and_then(|s| s.to_str()).unwrap_or("png");
    path.with_file_name(format!("{stem}_{nm}nm.{ext}"))
}

/// Every option checked, before any cell is read: the usage, `--starts`, the free parameters,
/// the material, the table's header and axes, the stride and the work it implies, and the
/// plot names of the bands against the inputs, the other outputs and each other.
fn prepare(
    args: &Args<'_>,
) -> Result<(polbrdf::MaterialSpec, Vec<Param>, PbsdfTable, usize), CliError> {
    if args.per_wavelength || args.index_out.is_some() || args.material_out.is_some() {
        return Err(CliError::Usage(
            "with a .pbsdf table the fit is per band already; --per-wavelength, --index-out and \
             --material-out do not apply"
                .into(),
        ));
    }
    let free = Param::parse_list(args.free).map_err(|e| CliError::Usage(format!("--free: {e}")))?;
    let base = crate::output::load_material(args.material)?;
    let table = PbsdfTable::open(args.data)?;
    let stride = plan(&table, args.subsample, args.starts).map_err(|e| match e {
        polbrdf_tasks::TaskError::Invalid { field, message } if field == "starts" => {
            CliError::Usage(format!("--starts: {message} (see docs/reliability.md)"))
        }
        e => e.into(),
    })?;
    if let Some(plot) = args.plot {
        let plots: Vec<PathBuf> = table
            .wavelengths_nm
            .iter()
            .map(|&nm| band_path(plot, nm))
            .collect();
        let mut outputs: Vec<&Path> = args.output.into_iter().collect();
        outputs.extend(plots.iter().map(PathBuf::as_path));
        polbrdf_io::check_distinct(&[args.data, Path::new(args.material)], &outputs)?;
    }
    Ok((base, free, table, stride))
}

/// The summary line of a band.
fn band_line(b: &BandFit, exclude: bool) -> String {
    let c = &b.counts;
    let mut line = format!(
        "  {} nm: {} cells used ({} below the horizon, {} NaN, {} not physically realizable{})",
        b.wavelength_nm,
        c.used,
        c.below_horizon,
        c.missing,
        c.inadmissible,
        if exclude { ", excluded" } else { ", kept" }
    );
    match &b.result {
        Ok(r) => {
            for (k, p) in r.params.iter().enumerate() {
                line += &format!("; {} = {:.6} ± {:.2e}", p.name(), r.values[k], r.stderr[k]);
            }
            line += &format!(
                "; χ²/dof = {:.3e}{}",
                r.reduced_chi2,
                if r.converged { "" } else { " NOT CONVERGED" }
            );
        }
        Err(e) => line += &format!("; refused: {e}"),
    }
    line
}

/// Runs `polbrdf fit` on a `.pbsdf` table.
pub fn run(args: &Args<'_>) -> Result<(), CliError> {
    let (base, free, mut table, s) = prepare(args)?;
    let opts = FitOptions {
        extra_starts: args.starts,
        seed: args.seed,
        ..FitOptions::default()
    };
    crate::note!(
        "polbrdf fit: {} — {}×{}×{} cells, {} band(s); every {s}th node along each axis; the 16 \
         entries of the pBRDF (psps basis) of each cell",
        args.data.display(),
        table.phi_d.len(),
        table.theta_d.len(),
        table.theta_h.len(),
        table.wavelengths_nm.len()
    );
    let exclude = args.exclude_inadmissible;
    let mut failed = Vec::new();
    let bands = table.wavelengths_nm.len() as u64;
    let bar = crate::progress::Progress::new(bands, "fit: bands");
    let mut done = 0;
    let doc = fit_table(&mut table, &base, &free, s, exclude, &opts, |fitted| {
        done += 1;
        bar.set(done, bands, None);
        let nm = fitted.wavelength_nm;
        match &fitted.result {
            Ok(r) => {
                if let Some(path) = args.plot {
                    crate::residuals::write_plot(&band_path(path, nm), r, &fitted.data)?;
                }
                if !r.converged {
                    failed.push(format!("{nm} nm: not converged"));
                }
            }
            Err(e) => failed.push(format!("{nm} nm: {e}")),
        }
        crate::note!("{}", band_line(fitted, exclude));
        Ok::<(), CliError>(())
    })?;
    drop(bar);
    let json = serde_json::to_string_pretty(&doc).expect("JSON of finite and null values");
    write_output(args.output, (json + "\n").as_bytes())?;
    if failed.is_empty() {
        Ok(())
    } else {
        Err(CliError::Invalid(format!(
            "the fit failed in {} band(s) ({}); the others were written",
            failed.len(),
            failed.join("; ")
        )))
    }
}
