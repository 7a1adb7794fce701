//! Mitsuba 3 `measured_polarized` tables (`.pbsdf`, docs/model.md §20): a material exported as
//! a table ([`export`]), and a table fitted band by band ([`fit_band`]).
//!
//! Resources (docs/io.md, Resource model): the export holds [`polbrdf_io::pbsdf::CELL_BLOCK`]
//! cells at a time whatever the grid, and its file is at most [`MAX_EXPORT_BYTES`]; the fit
//! reads only the cells it keeps (64 bytes each, never a whole slab), so its memory is that of
//! the subsampled data, and its work, starts × kept cells, is at most [`MAX_FIT_WORK`] a band.

use crate::{TaskError, TaskResult};
use polbrdf::geometry::rusinkiewicz::{cell_geometry, from_reflection_frame, to_reflection_frame};
use polbrdf::{Engine, GeometryBatch, Material, MaterialSpec, Mueller};
use polbrdf_fit::{fit, FitOptions, FitResult, Measurement, Observable, Param};
use polbrdf_io::PbsdfTable;
use std::path::Path;

/// Bands of a table the stock plugin reads.
pub const PLUGIN_BANDS: usize = 5;

/// The default bands of an export (nm): the KAIST wavelengths, the only band count the stock
/// plugin reads.
pub const DEFAULT_BANDS_NM: [u16; PLUGIN_BANDS] = [450, 500, 550, 600, 650];

/// The default export grid: φ_d 10°, θ_d 2°, θ_h 1° (about 50 MB).
pub const DEFAULT_GRID: [usize; 3] = [37, 46, 91];

/// Nodes of an export grid axis.
pub const GRID_NODES: std::ops::RangeInclusive<usize> = 2..=4096;

/// Largest `.pbsdf` file an export writes (bytes of the matrices): 4 GiB, four times the
/// KAIST tables at full resolution (361 × 91 × 91 cells × 5 bands, 0.96 GB), and more than
/// the plugin's GPU copy of a table comfortably holds.
pub const MAX_EXPORT_BYTES: u64 = 1 << 32;

/// Cells kept per band when no stride is given.
pub const AUTO_CELLS: usize = 20_000;

/// Largest work of one band's fit: (extra starts + 1) × cells kept. Each start is a full
/// Levenberg–Marquardt fit of 16 values a cell; 4·10⁶ is about 70 times the default (3 starts
/// × 20 000 cells), a few minutes on one core.
pub const MAX_FIT_WORK: usize = 4_000_000;

/// Tolerance of the realizability check (coherency eigenvalues ≥ −tol·M00): float32 tables of
/// non-depolarizing matrices round their zero eigenvalues to about 1e-7·M00.
pub const REALIZABLE_TOL: f64 = 1e-4;

/// Whether `path` names a `.pbsdf` table (by its extension).
pub fn is_pbsdf(path: &Path) -> bool {
    path.extension().and_then(|e| e.to_str()) == Some("pbsdf")
}

/// What [`export`] writes: band wavelengths (nm) and node counts along φ_d, θ_d, θ_h.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ExportRequest {
    /// Band wavelengths in nm, increasing; the plugin reads exactly [`PLUGIN_BANDS`].
    pub bands_nm: Vec<u16>,
    /// Uniform nodes along φ_d ∈ [−π, π], θ_d ∈ [0, π/2], θ_h ∈ [0, π/2].
    pub grid: [usize; 3],
}

impl ExportRequest {
    /// Bytes of the matrices the request writes.
    pub fn matrix_bytes(&self) -> u64 {
        self.grid.iter().map(|&n| n as u64).product::<u64>() * self.bands_nm.len() as u64 * 64
    }

    /// Checks the request (before anything is computed or written).
    ///
    /// # Errors
    /// [`TaskError::Invalid`] naming `bands_nm` or `grid`.
    pub fn validate(&self) -> TaskResult<()> {
        let b = &self.bands_nm;
        if b.contains(&0) || b.windows(2).any(|w| w[1] <= w[0]) {
            return Err(TaskError::invalid(
                "bands_nm",
                "the wavelengths (nm, integers 1–65535) must increase",
            ));
        }
        if b.len() != PLUGIN_BANDS {
            return Err(TaskError::invalid(
                "bands_nm",
                format!(
                    "{} band(s): Mitsuba's measured_polarized plugin reads exactly five wavelengths",
                    b.len()
                ),
            ));
        }
        if !self.grid.iter().all(|n| GRID_NODES.contains(n)) {
            return Err(TaskError::invalid(
                "grid",
                "three node counts P,D,H, each 2–4096, are required",
            ));
        }
        let bytes = self.matrix_bytes();
        if bytes > MAX_EXPORT_BYTES {
            let [p, d, h] = self.grid;
            return Err(TaskError::invalid(
                "grid",
                format!(
                    "{p}×{d}×{h} cells × {} bands is {:.1} GB of table: at most {:.1} GB \
                     ({MAX_EXPORT_BYTES} bytes) are written (fewer nodes)",
                    b.len(),
                    bytes as f64 / 1e9,
                    MAX_EXPORT_BYTES as f64 / 1e9
                ),
            ));
        }
        Ok(())
    }
}

/// `n` uniform nodes from `a` to `b`, as stored (float32), so that each cell holds the model at
/// the node the plugin and the reader see, not 1e-8 rad away (which matters at the horizon).
fn stored_nodes(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| f64::from((a + (b - a) * i as f64 / (n - 1) as f64) as f32))
        .collect()
}

/// Cells `range` (indices `d · n_theta_h + h`) of the slab at `phi_d` (C order `[cell, band,
/// 4, 4]`, float32): one batch call per band, rotated to the plane-of-reflection frame; zero
/// below the horizon.
pub fn cells(
    materials: &[Material],
    phi_d: f64,
    theta_d: &[f64],
    theta_h: &[f64],
    range: std::ops::Range<usize>,
) -> TaskResult<Vec<f32>> {
    let nh = theta_h.len();
    let geoms = range
        .map(|c| cell_geometry(phi_d, theta_d[c / nh], theta_h[c % nh]))
        .collect::<Result<Vec<_>, _>>()?;
    let cols: [Vec<f64>; 4] = [
        geoms.iter().map(|g| g.theta_i()).collect(),
        geoms.iter().map(|g| g.phi_i()).collect(),
        geoms.iter().map(|g| g.theta_r()).collect(),
        geoms.iter().map(|g| g.phi_r()).collect(),
    ];
    let batch = GeometryBatch::new(&cols[0], &cols[1], &cols[2], &cols[3])?;
    let vars: Vec<_> = geoms.iter().map(|g| g.angle_variables()).collect();
    let nb = materials.len();
    let mut out = vec![0f32; geoms.len() * nb * 16];
    for (b, m) in materials.iter().enumerate() {
        let f = Engine::new(m).mueller(&batch)?;
        for (c, (fc, v)) in f.iter().zip(&vars).enumerate() {
            let Some(v) = v else { continue };
            let t = to_reflection_frame(&Mueller::from_row_major(fc), v).to_row_major();
            let at = (c * nb + b) * 16;
            for (o, x) in out[at..at + 16].iter_mut().zip(t) {
                *o = x as f32;
            }
        }
    }
    Ok(out)
}

/// Writes `spec` as a `.pbsdf` table at `path` (through the output layer); returns the bytes of
/// its matrices. The request is validated first, so nothing is computed for a refused one.
///
/// # Errors
/// [`TaskError::Invalid`] for the request; [`TaskError::Model`] when the material cannot be
/// built at a band; [`TaskError::Io`] for the output.
pub fn export(spec: &MaterialSpec, req: &ExportRequest, path: &Path) -> TaskResult<u64> {
    export_with_progress(spec, req, path, &mut |_, _| {})
}

/// [`export`], calling `progress(done, total)` after each φ_d slab is computed (for a progress
/// bar: the adapters draw it; `total` is the number of slabs).
///
/// # Errors
/// As [`export`].
pub fn export_with_progress(
    spec: &MaterialSpec,
    req: &ExportRequest,
    path: &Path,
    progress: &mut dyn FnMut(usize, usize),
) -> TaskResult<u64> {
    req.validate()?;
    let materials = req
        .bands_nm
        .iter()
        .map(|&nm| spec.build_at(f64::from(nm) / 1000.0))
        .collect::<Result<Vec<_>, _>>()?;
    let [p, d, h] = req.grid;
    let pi = std::f64::consts::PI;
    let phi_d = stored_nodes(-pi, pi, p);
    let theta_d = stored_nodes(0.0, pi / 2.0, d);
    let theta_h = stored_nodes(0.0, pi / 2.0, h);
    polbrdf_io::write_pbsdf(
        path,
        &phi_d,
        &theta_d,
        &theta_h,
        &req.bands_nm,
        |k, range| {
            let slab_done = range.end == d * h;
            let out = cells(&materials, phi_d[k], &theta_d, &theta_h, range);
            if slab_done {
                progress(k + 1, p);
            }
            out
        },
    )?;
    Ok(req.matrix_bytes())
}

/// Cells kept by stride `s` along every axis of `table`.
fn kept(table: &PbsdfTable, s: usize) -> usize {
    table.phi_d.len().div_ceil(s)
        * table.theta_d.len().div_ceil(s)
        * table.theta_h.len().div_ceil(s)
}

/// A band fit's plan: the stride, and the work checked against [`MAX_FIT_WORK`] — from the
/// table's axes only, before any cell is read.
///
/// # Errors
/// [`TaskError::Invalid`] naming `subsample` or `starts`.
pub fn plan(table: &PbsdfTable, subsample: Option<usize>, starts: usize) -> TaskResult<usize> {
    if starts > polbrdf_fit::MAX_EXTRA_STARTS {
        return Err(TaskError::invalid(
            "starts",
            format!("{starts}: at most {}", polbrdf_fit::MAX_EXTRA_STARTS),
        ));
    }
    let s = match subsample {
        Some(0) => return Err(TaskError::invalid("subsample", "0: the stride must be ≥ 1")),
        Some(s) => s,
        None => (1..)
            .find(|&s| kept(table, s) <= AUTO_CELLS)
            .expect("stride large enough"),
    };
    let cells = kept(table, s);
    match cells.checked_mul(starts + 1) {
        Some(w) if w <= MAX_FIT_WORK => Ok(s),
        _ => Err(TaskError::invalid(
            "starts",
            format!(
                "{} start(s) × {cells} cells kept (stride {s}) is more than {MAX_FIT_WORK} \
                 cell fits a band: fewer starts, or a larger subsample stride",
                starts + 1
            ),
        )),
    }
}

/// Counts of one band's cells.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct BandCounts {
    /// Cells visited.
    pub cells: usize,
    /// Below the horizon (no geometry).
    pub below_horizon: usize,
    /// Holding a NaN or infinite entry.
    pub missing: usize,
    /// Not physically realizable.
    pub inadmissible: usize,
    /// Used in the fit.
    pub used: usize,
}

/// One band's measurements: the 16 entries of the psps pBRDF of every kept cell, each cell read
/// on its own (memory: the kept cells only).
///
/// # Errors
/// [`TaskError::Io`] reading the table; [`TaskError::Model`] for a node outside the domain.
pub fn band_data(
    table: &mut PbsdfTable,
    band: usize,
    stride: usize,
    exclude_inadmissible: bool,
    wavelength_um: Option<f64>,
) -> TaskResult<(Vec<Measurement>, BandCounts)> {
    let (np, nd, nh) = (table.phi_d.len(), table.theta_d.len(), table.theta_h.len());
    let mut data = Vec::new();
    let mut c = BandCounts::default();
    for p in (0..np).step_by(stride) {
        for d in (0..nd).step_by(stride) {
            for h in (0..nh).step_by(stride) {
                c.cells += 1;
                let g = cell_geometry(table.phi_d[p], table.theta_d[d], table.theta_h[h])?;
                let Some(v) = g.angle_variables() else {
                    c.below_horizon += 1;
                    continue;
                };
                let t = table.read_cell(p, d, h, band)?.map(f64::from);
                if t.iter().any(|x| !x.is_finite()) {
                    c.missing += 1;
                    continue;
                }
                let f = from_reflection_frame(&Mueller::from_row_major(&t), &v);
                if !f.is_physically_realizable(REALIZABLE_TOL) {
                    c.inadmissible += 1;
                    if exclude_inadmissible {
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

/// One band's fit.
#[derive(Debug)]
pub struct BandFit {
    /// The band's wavelength (nm).
    pub wavelength_nm: u16,
    /// Its cells.
    pub counts: BandCounts,
    /// The measurements fitted.
    pub data: Vec<Measurement>,
    /// The fit, or why it was refused.
    pub result: Result<FitResult, polbrdf_fit::FitError>,
}

/// Fits band `band` of `table` (stride from [`plan`]).
///
/// # Errors
/// As [`band_data`] (a refused fit is in [`BandFit::result`]).
pub fn fit_band(
    table: &mut PbsdfTable,
    band: usize,
    base: &MaterialSpec,
    free: &[Param],
    stride: usize,
    exclude_inadmissible: bool,
    opts: &FitOptions,
) -> TaskResult<BandFit> {
    let nm = table.wavelengths_nm[band];
    let wl = base.is_spectral().then_some(f64::from(nm) / 1000.0);
    let (data, counts) = band_data(table, band, stride, exclude_inadmissible, wl)?;
    let result = fit(base, free, &data, opts);
    Ok(BandFit {
        wavelength_nm: nm,
        counts,
        data,
        result,
    })
}

impl BandFit {
    /// The band's entry of `fit.json` (`per_band[k]`): the fit's document
    /// ([`crate::fit::to_json`]) with the band's wavelength and cell counts, or why it was
    /// refused.
    pub fn to_json(&self, data: &Path, exclude_inadmissible: bool) -> serde_json::Value {
        let c = &self.counts;
        let counts = serde_json::json!({"cells": c.cells, "below_horizon": c.below_horizon,
            "missing_nan": c.missing, "inadmissible": c.inadmissible,
            "inadmissible_excluded": exclude_inadmissible, "cells_used": c.used});
        match &self.result {
            Ok(r) => {
                let mut v = crate::fit::to_json(r, data);
                v["wavelength_nm"] = self.wavelength_nm.into();
                v["table"] = counts;
                v
            }
            Err(e) => serde_json::json!({"wavelength_nm": self.wavelength_nm,
                "refused": e.to_string(), "table": counts}),
        }
    }
}

/// Fits every band of `table` in turn ([`fit_band`], stride from [`plan`]) and returns the
/// `fit.json` document ([`document`]). `each` sees every band's fit as soon as it is done (for
/// residual plots, summaries and progress) and may stop the run with its error; no band's
/// data outlives its turn.
///
/// # Errors
/// As [`fit_band`]; what `each` returns.
#[allow(clippy::too_many_arguments)] // The fit's inputs, each a plain value of the request.
pub fn fit_table<E: From<TaskError>>(
    table: &mut PbsdfTable,
    base: &MaterialSpec,
    free: &[Param],
    stride: usize,
    exclude_inadmissible: bool,
    opts: &FitOptions,
    mut each: impl FnMut(&BandFit) -> Result<(), E>,
) -> Result<serde_json::Value, E> {
    let data = table.path().to_path_buf();
    let mut bands = Vec::new();
    for b in 0..table.wavelengths_nm.len() {
        let fitted = fit_band(table, b, base, free, stride, exclude_inadmissible, opts)?;
        each(&fitted)?;
        bands.push(fitted.to_json(&data, exclude_inadmissible));
    }
    Ok(document(bands, free, &data, stride))
}

/// The `fit.json` document of a table's band fits, from their entries ([`BandFit::to_json`],
/// taken band by band so that no band's data outlives its fit).
pub fn document(
    per_band: Vec<serde_json::Value>,
    free: &[Param],
    data: &Path,
    stride: usize,
) -> serde_json::Value {
    serde_json::json!({
        "per_band": per_band,
        "parameter_order": free.iter().map(|p| p.name()).collect::<Vec<_>>(),
        "data": data.display().to_string(),
        "subsample": stride,
        "fitted": "m00..m33 of the psps pBRDF of every cell (unweighted; uncertainties from the residuals)",
    })
}
