//! `polbrdf fit --data table.pbsdf`: the fit of a measured Mitsuba 3 table (docs/model.md §20),
//! one band at a time, streamed (one φ_d slab in memory), on a subsampled grid.

use crate::error::CliError;
use crate::fit::{residual_figure, to_json, Args};
use crate::output::write_output;
use polbrdf::geometry::rusinkiewicz::{cell_geometry, from_reflection_frame};
use polbrdf::Mueller;
use polbrdf_fit::{fit, FitOptions, Measurement, Observable, Param};
use polbrdf_io::PbsdfTable;
use serde_json::{json, Value};
use std::path::{Path, PathBuf};

/// Cells kept per band when `--subsample` is not given.
pub const AUTO_CELLS: usize = 20_000;

/// Tolerance of the realizability check (coherency eigenvalues ≥ −tol·M00): float32 tables of
/// non-depolarizing matrices round their zero eigenvalues to about 1e-7·M00.
pub const REALIZABLE_TOL: f64 = 1e-4;

/// Whether `path` names a `.pbsdf` table.
pub fn is_pbsdf(path: &Path) -> bool {
    path.extension().and_then(|e| e.to_str()) == Some("pbsdf")
}

/// The stride: the given one, or the smallest keeping at most [`AUTO_CELLS`] cells.
fn stride(table: &PbsdfTable, given: Option<usize>) -> Result<usize, CliError> {
    let kept = |s: usize| {
        table.phi_d.len().div_ceil(s)
            * table.theta_d.len().div_ceil(s)
            * table.theta_h.len().div_ceil(s)
    };
    match given {
        Some(0) => Err(CliError::Invalid(
            "--subsample 0: the stride must be ≥ 1".into(),
        )),
        Some(s) => Ok(s),
        None => Ok((1..)
            .find(|&s| kept(s) <= AUTO_CELLS)
            .expect("stride large enough")),
    }
}

/// Counts of one band's cells.
#[derive(Debug, Default, Clone, Copy)]
struct Counts {
    cells: usize,
    below_horizon: usize,
    missing: usize,
    inadmissible: usize,
    used: usize,
}

/// One band's measurements: the 16 entries of the psps pBRDF of every kept cell.
fn band_data(
    table: &mut PbsdfTable,
    band: usize,
    stride: usize,
    exclude: bool,
    wavelength_um: Option<f64>,
) -> Result<(Vec<Measurement>, Counts), CliError> {
    let (nd, nh, nb) = (
        table.theta_d.len(),
        table.theta_h.len(),
        table.wavelengths_nm.len(),
    );
    let mut slab = Vec::new();
    let mut data = Vec::new();
    let mut c = Counts::default();
    for p in (0..table.phi_d.len()).step_by(stride) {
        table.read_slab(p, &mut slab)?;
        for d in (0..nd).step_by(stride) {
            for h in (0..nh).step_by(stride) {
                c.cells += 1;
                let g = cell_geometry(table.phi_d[p], table.theta_d[d], table.theta_h[h])?;
                let Some(v) = g.angle_variables() else {
                    c.below_horizon += 1;
                    continue;
                };
                let at = ((d * nh + h) * nb + band) * 16;
                let t: [f64; 16] = std::array::from_fn(|k| f64::from(slab[at + k]));
                if t.iter().any(|x| !x.is_finite()) {
                    c.missing += 1;
                    continue;
                }
                let f = from_reflection_frame(&Mueller::from_row_major(&t), &v);
                if !f.is_physically_realizable(REALIZABLE_TOL) {
                    c.inadmissible += 1;
                    if exclude {
                        continue;
                    }
                }
                c.used += 1;
                for i in 0..4 {
                    for j in 0..4 {
                        data.push(Measurement {
                            geometry: g,
                            observable: Observable::Mueller(i, j),
                            value: f[(i, j)],
                            sigma: None,
                            wavelength_um,
                        });
                    }
                }
            }
        }
    }
    Ok((data, c))
}

fn band_path(path: &Path, nm: u16) -> PathBuf {
    let stem = path
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("residuals");
    let ext = path.extension().and_then(|s| s.to_str()).unwrap_or("png");
    path.with_file_name(format!("{stem}_{nm}nm.{ext}"))
}

/// Runs `polbrdf fit` on a `.pbsdf` table.
pub fn run(args: &Args<'_>) -> Result<(), CliError> {
    if args.per_wavelength || args.index_out.is_some() || args.material_out.is_some() {
        return Err(CliError::Usage(
            "with a .pbsdf table the fit is per band already; --per-wavelength, --index-out and \
             --material-out do not apply"
                .into(),
        ));
    }
    let base = polbrdf_io::load_material(args.material)?;
    let free = Param::parse_list(args.free)?;
    let mut table = PbsdfTable::open(args.data)?;
    let s = stride(&table, args.subsample)?;
    let opts = FitOptions {
        extra_starts: args.starts,
        seed: args.seed,
        ..FitOptions::default()
    };
    eprintln!(
        "polbrdf fit: {} — {}×{}×{} cells, {} band(s); every {s}th node along each axis; the 16 \
         entries of the pBRDF (psps basis) of each cell",
        args.data.display(),
        table.phi_d.len(),
        table.theta_d.len(),
        table.theta_h.len(),
        table.wavelengths_nm.len()
    );
    let mut bands = Vec::new();
    let mut failed = Vec::new();
    for b in 0..table.wavelengths_nm.len() {
        let nm = table.wavelengths_nm[b];
        let wl = base.is_spectral().then_some(f64::from(nm) / 1000.0);
        let (data, c) = band_data(&mut table, b, s, args.exclude_inadmissible, wl)?;
        let counts = json!({"cells": c.cells, "below_horizon": c.below_horizon, "missing_nan": c.missing,
            "inadmissible": c.inadmissible, "inadmissible_excluded": args.exclude_inadmissible,
            "cells_used": c.used});
        let mut line = format!(
            "  {nm} nm: {} cells used ({} below the horizon, {} NaN, {} not physically realizable{})",
            c.used,
            c.below_horizon,
            c.missing,
            c.inadmissible,
            if args.exclude_inadmissible { ", excluded" } else { ", kept" }
        );
        match fit(&base, &free, &data, &opts) {
            Ok(r) => {
                for (k, p) in r.params.iter().enumerate() {
                    line += &format!("; {} = {:.6} ± {:.2e}", p.name(), r.values[k], r.stderr[k]);
                }
                line += &format!(
                    "; χ²/dof = {:.3e}{}",
                    r.reduced_chi2,
                    if r.converged { "" } else { " NOT CONVERGED" }
                );
                if let Some(path) = args.plot {
                    let fig = residual_figure(&r, &data);
                    let path = band_path(path, nm);
                    let bytes = match path.extension().and_then(|e| e.to_str()) {
                        Some("svg") => fig.svg().map_err(CliError::Plot)?.into_bytes(),
                        _ => fig.png().map_err(CliError::Plot)?,
                    };
                    polbrdf_io::write_atomic(&path, &bytes)?;
                }
                if !r.converged {
                    failed.push(format!("{nm} nm: not converged"));
                }
                let mut v = to_json(&r, args.data);
                v["wavelength_nm"] = Value::from(nm);
                v["table"] = counts;
                bands.push(v);
            }
            Err(e) => {
                line += &format!("; refused: {e}");
                failed.push(format!("{nm} nm: {e}"));
                bands.push(json!({"wavelength_nm": nm, "refused": e.to_string(), "table": counts}));
            }
        }
        eprintln!("{line}");
    }
    let doc = json!({
        "per_band": bands,
        "parameter_order": free.iter().map(|p| p.name()).collect::<Vec<_>>(),
        "data": args.data.display().to_string(),
        "subsample": s,
        "fitted": "m00..m33 of the psps pBRDF of every cell (unweighted; uncertainties from the residuals)",
    });
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
