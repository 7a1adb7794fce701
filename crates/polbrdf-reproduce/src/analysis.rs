//! Everything computed for the report, in one place: the figures' data and the numbers that
//! decide each of the paper's claims.

use crate::compute::{self, Fig2, IndexFit, Interpretation, Roughness, Smooth};
use crate::params::*;
use polbrdf::analysis::emission::Emissivity;
use polbrdf::Form;

/// Spread of one Fig. 2 curve (claim 3).
#[derive(Debug, Clone, Copy)]
pub struct Spread {
    /// Incidence angle, degrees.
    pub theta_deg: f64,
    /// Largest value (at the smallest θN), sr⁻¹.
    pub max: f64,
    /// Smallest value (at θN = 60°), sr⁻¹.
    pub min: f64,
    /// The same two with shadowing off.
    pub max_off: f64,
    /// See `max_off`.
    pub min_off: f64,
    /// SO at θN = 60° (the shadowing factor at the end of the curve).
    pub so_end: f64,
}

impl Spread {
    /// max − min, sr⁻¹.
    pub fn abs(&self) -> f64 {
        self.max - self.min
    }
    /// max − min with shadowing off, sr⁻¹.
    pub fn abs_off(&self) -> f64 {
        self.max_off - self.min_off
    }
    /// log10(max/min): the spread on the log axis, decades.
    pub fn decades(&self) -> f64 {
        (self.max / self.min).log10()
    }
    /// log10(max/min) with shadowing off.
    pub fn decades_off(&self) -> f64 {
        (self.max_off / self.min_off).log10()
    }
}

/// One roughness interpretation evaluated at Table 1's cells.
#[derive(Debug, Clone)]
pub struct InterpResult {
    /// Label used in the report, e.g. "(a) σ in rad + volume term, eq. 6 form".
    pub label: String,
    /// The interpretation.
    pub how: Roughness,
    /// DoLP in % at Table 1's cells.
    pub cells: [[f64; 5]; 6],
    /// RMS vs the paper's own model column, percentage points.
    pub rms_model: f64,
    /// RMS vs the Lawrence/Wolff column.
    pub rms_lawrence: f64,
    /// RMS of the relative effect DoLP(r)/DoLP(0) vs the paper's model column, % of row 0.
    pub rel_model: f64,
    /// The same vs the Lawrence/Wolff column.
    pub rel_lawrence: f64,
}

/// Index fits of Table 1's row 0 under one smooth-surface hypothesis and one column.
#[derive(Debug, Clone, Copy)]
pub struct Row0Fit {
    /// Reflection or emission.
    pub hyp: Smooth,
    /// 0: the paper's model column, 1: the Lawrence/Wolff column.
    pub column: usize,
    /// RMS at the paper's n = 1.65.
    pub rms_paper_n: f64,
    /// Best real n.
    pub real: IndexFit,
    /// Best complex n + ik.
    pub complex: IndexFit,
}

/// All results.
#[derive(Debug, Clone)]
pub struct Analysis {
    /// Fig. 2 data.
    pub fig2: Fig2,
    /// Spread of each Fig. 2 curve.
    pub spreads: Vec<Spread>,
    /// Every Fig. 2 curve strictly decreases with θN.
    pub fig2_decreasing: bool,
    /// At every θN the curves are ordered by incidence angle (larger θ, larger f).
    pub fig2_ordered: bool,
    /// Pairs of Fig. 2 curves (θ_low°, θ_high°, θN° of first crossing) where the curve of the
    /// larger incidence angle drops to or below the other one.
    pub crossings: Vec<(f64, f64, f64)>,
    /// Fig. 3 data: (θ°, DoLP).
    pub fig3: Vec<(f64, f64)>,
    /// Where Fig. 3 peaks: (θ°, DoLP).
    pub fig3_peak: (f64, f64),
    /// Angles of the DoLP curves (degrees).
    pub dolp_angles: Vec<f64>,
    /// Fig. 4 data (primary interpretation): DoLP per roughness row at `dolp_angles`.
    pub fig4: Vec<Vec<f64>>,
    /// Interpretations; index 0 is the primary one (Fig. 4, Table 1 CSV).
    pub interps: Vec<InterpResult>,
    /// Largest |DoLP(σ) − DoLP(0)| over the Fig. 4 grid when there is no volume term.
    pub no_volume_max_change: f64,
    /// Row-0 fits: reflection/emission × the two columns.
    pub row0: Vec<Row0Fit>,
    /// Index used for the rough-emission interpretation (best real n, emission, Lawrence column).
    pub emission_n: f64,
    /// Fig. 5(b) curves at `dolp_angles`: (legend, DoLP fractions).
    pub hypothesis_curves: Vec<(String, Vec<f64>)>,
    /// Diagnostics of interpretation (c), from the core's Kirchhoff emissivity.
    pub emission_notes: EmissionNotes,
}

/// The diagnostics of interpretation (c), every number from the core's Kirchhoff emissivity
/// (`polbrdf::analysis::emission::emissivities`, the one [`Interpretation::emissivities_at`]
/// calls): validity and reciprocity per cell, the energy balance behind the result, the variant
/// without shadowing, and the check of the σ → 0 row.
#[derive(Debug, Clone)]
pub struct EmissionNotes {
    /// The (real) index of (c).
    pub n: f64,
    /// (c) itself (shadowing on) at Table 1's rough cells: `cells[r − 1][c]` for the roughness
    /// row `r` = 1…5 (σ = 0.1…0.5 rad) and the angle column `c`.
    pub cells: Vec<[Emissivity; 5]>,
    /// The same with shadowing off, the variant (c′).
    pub cells_no_so: Vec<[Emissivity; 5]>,
    /// DoLP in % of (c′) at Table 1's cells (row 0: the Fresnel limit; cells that are not
    /// physically valid included as the core gives them).
    pub dolp_no_so: [[f64; 5]; 6],
    /// RMS of (c′) over its physically valid cells against (the paper's model column, the
    /// Lawrence/Wolff column), percentage points, and the number of those cells.
    pub rms_no_so_valid: (f64, f64, usize),
    /// The flat-surface (Fresnel) emissivities `(1 − R_s, 1 − R_p)` at Table 1's angles.
    pub flat: [(f64, f64); 5],
    /// `max_θ |DoLP(σ) − DoLP_Fresnel(θ)|` (fraction) over Table 1's angles at σ =
    /// `SMOOTH_CHECK_SIGMA_DEG` with shadowing off.
    pub smooth_gap_no_so: f64,
    /// The same with shadowing on, at σ = `SMOOTH_CHECK_SIGMA_DEG` and at twice it.
    pub smooth_gap_so: (f64, f64),
}

impl EmissionNotes {
    /// Largest reciprocity residual `max |ε − ε_B|` over the cells of `grid`.
    pub fn max_residual(grid: &[[Emissivity; 5]]) -> f64 {
        grid.iter()
            .flatten()
            .map(Emissivity::reciprocity_residual)
            .fold(0.0, f64::max)
    }

    /// Largest `|ε2|, |ε3|` over the cells of `grid` (0 for this isotropic model by symmetry).
    pub fn max_eps23(grid: &[[Emissivity; 5]]) -> f64 {
        grid.iter()
            .flatten()
            .map(|e| e.eps.0[2].abs().max(e.eps.0[3].abs()))
            .fold(0.0, f64::max)
    }

    /// The cells of `grid` that are not physically valid ([`Emissivity::is_valid`]: ε_s or ε_p
    /// outside [0, 1]), as `(row, column, emissivity)` with `row` into `ROUGHNESS`.
    pub fn invalid(grid: &[[Emissivity; 5]]) -> Vec<(usize, usize, Emissivity)> {
        let mut out = Vec::new();
        for (r, row) in grid.iter().enumerate() {
            for (c, e) in row.iter().enumerate() {
                if !e.is_valid() {
                    out.push((r + 1, c, *e));
                }
            }
        }
        out
    }
}

/// The emissivities of a (c)-type interpretation at Table 1's rough cells.
fn emission_cells(it: &Interpretation) -> Result<Vec<[Emissivity; 5]>, polbrdf::Error> {
    let rad: Vec<f64> = TABLE_ANGLES_DEG.iter().map(|t| t.to_radians()).collect();
    (1..ROUGHNESS.len())
        .map(|ri| {
            let e = it.emissivities_at(ri, &rad).ok_or_else(|| {
                polbrdf::Error::InconsistentParameters(
                    "not a thermal-emission interpretation".into(),
                )
            })??;
            e.try_into().map_err(|_| {
                polbrdf::Error::InconsistentParameters("one emissivity per angle".into())
            })
        })
        .collect()
}

/// The diagnostics of interpretation (c) with index `n`; `with_so` is (c) itself.
fn emission_notes(n: f64, with_so: &Interpretation) -> Result<EmissionNotes, polbrdf::Error> {
    let cells = emission_cells(with_so)?;
    let no_so = Interpretation::new(Roughness::Emission(n, false))?;
    let cells_no_so = emission_cells(&no_so)?;
    let dolp_no_so = compute::table_cells(&no_so);
    let (mut s_model, mut s_lawrence, mut count) = (0.0, 0.0, 0usize);
    for (ri, row) in dolp_no_so.iter().enumerate() {
        for (ci, &d) in row.iter().enumerate() {
            if ri == 0 || cells_no_so[ri - 1][ci].is_valid() {
                s_model += (d - TABLE_PAPER_MODEL[ri][ci]).powi(2);
                s_lawrence += (d - TABLE_PAPER_LAWRENCE[ri][ci]).powi(2);
                count += 1;
            }
        }
    }
    let rms = |s: f64| (s / count.max(1) as f64).sqrt();
    let mut flat = [(0.0, 0.0); 5];
    for (f, t) in flat.iter_mut().zip(TABLE_ANGLES_DEG) {
        let (rs, rp) = compute::fresnel_rs_rp(n, 0.0, t.to_radians());
        *f = (1.0 - rs, 1.0 - rp);
    }
    let rad: Vec<f64> = TABLE_ANGLES_DEG.iter().map(|t| t.to_radians()).collect();
    let gap = |sigma_deg: f64, shadowing: bool| -> Result<f64, polbrdf::Error> {
        let m = compute::emission_material(n, sigma_deg.to_radians(), shadowing)?;
        Ok(compute::emission_dolp(&m, &rad)
            .iter()
            .zip(&rad)
            .map(|(d, &t)| (d - Smooth::Emission.dolp(n, 0.0, t)).abs())
            .fold(0.0, f64::max))
    };
    Ok(EmissionNotes {
        n,
        cells,
        cells_no_so,
        dolp_no_so,
        rms_no_so_valid: (rms(s_model), rms(s_lawrence), count),
        flat,
        smooth_gap_no_so: gap(SMOOTH_CHECK_SIGMA_DEG, false)?,
        smooth_gap_so: (
            gap(SMOOTH_CHECK_SIGMA_DEG, true)?,
            gap(2.0 * SMOOTH_CHECK_SIGMA_DEG, true)?,
        ),
    })
}

impl Analysis {
    /// The primary interpretation.
    pub fn primary(&self) -> &InterpResult {
        &self.interps[0]
    }
}

/// Fig. 2 and its statistics.
pub fn fig2_part() -> Result<(Fig2, Vec<Spread>, bool, bool), polbrdf::Error> {
    let f = compute::fig2()?;
    let so_m = compute::material(Form::Paper, FIG2_SIGMA_DEG, 0.0, 0.0, true)?;
    let last = f.theta_n_deg.len() - 1;
    let spreads = f
        .thetas_deg
        .iter()
        .enumerate()
        .map(|(i, &t)| {
            let v = polbrdf::AngleVariables::in_plane_specular(
                t.to_radians(),
                f.theta_n_deg[last].to_radians(),
            );
            let so_end = so_m.evaluate_angles(&v).terms.map_or(f64::NAN, |x| x.so);
            Spread {
                theta_deg: t,
                max: f.brdf[i][0],
                min: f.brdf[i][last],
                max_off: f.brdf_no_shadow[i][0],
                min_off: f.brdf_no_shadow[i][last],
                so_end,
            }
        })
        .collect();
    let decreasing = f.brdf.iter().all(|c| c.windows(2).all(|w| w[1] < w[0]));
    let ordered = (0..f.theta_n_deg.len()).all(|j| f.brdf.windows(2).all(|w| w[1][j] > w[0][j]));
    Ok((f, spreads, decreasing, ordered))
}

/// For every pair of Fig. 2 curves, the first θN at which the larger incidence angle no longer
/// gives the larger BRDF.
pub fn crossings(f: &Fig2) -> Vec<(f64, f64, f64)> {
    let mut out = Vec::new();
    for i in 0..f.thetas_deg.len() {
        for j in i + 1..f.thetas_deg.len() {
            if let Some(k) = (0..f.theta_n_deg.len()).find(|&k| f.brdf[j][k] <= f.brdf[i][k]) {
                out.push((f.thetas_deg[i], f.thetas_deg[j], f.theta_n_deg[k]));
            }
        }
    }
    out
}

/// Runs every computation; `tick` is called after each of `STEPS` steps: Fig. 2 (claims 1–3′),
/// Fig. 3 (claim 4), the fits of Table 1's row 0 (claim 7, Fig. 5(b)) and each roughness
/// interpretation (claims 5 and 6, Fig. 4, Table 1, Fig. 5(a)).
pub fn analyze(tick: &mut dyn FnMut(&str)) -> Result<Analysis, polbrdf::Error> {
    let (fig2, spreads, fig2_decreasing, fig2_ordered) = fig2_part()?;
    let crossings = crossings(&fig2);
    tick("Fig. 2 computed");

    let fig3 = compute::fig3()?;
    let fig3_peak = fig3_peak(&fig3);
    let dolp_angles = compute::dolp_angles_deg();
    tick("Fig. 3 computed");

    let row0 = row0_fits();
    let emission_n = fitted_n(&row0, Smooth::Emission, 1);
    let hypothesis_curves = hypothesis_curves(&row0, &dolp_angles);
    tick("Table 1 row 0 fitted");

    let r = roughness_part(emission_n, &dolp_angles, tick)?;
    Ok(Analysis {
        fig2,
        crossings,
        emission_notes: r.emission_notes,
        spreads,
        fig2_decreasing,
        fig2_ordered,
        fig3,
        fig3_peak,
        dolp_angles,
        fig4: r.fig4,
        interps: r.interps,
        no_volume_max_change: r.no_volume_max_change,
        row0,
        emission_n,
        hypothesis_curves,
    })
}

/// Where the Fig. 3 curve peaks, `(θ°, DoLP)` (claim 4: at Brewster's angle, DoLP 1).
fn fig3_peak(fig3: &[(f64, f64)]) -> (f64, f64) {
    fig3.iter().copied().fold(
        (f64::NAN, f64::NEG_INFINITY),
        |a, b| if b.1 > a.1 { b } else { a },
    )
}

/// Table 1's row 0 (σ → 0) fitted by each smooth-surface hypothesis (reflection, emission)
/// against each column (the paper's model, Lawrence/Wolff): the RMS at the paper's n and the
/// best real and complex indices (claim 7: is the row the Fresnel DoLP of n = 1.65?).
fn row0_fits() -> Vec<Row0Fit> {
    let columns = [&TABLE_PAPER_MODEL[0], &TABLE_PAPER_LAWRENCE[0]];
    let mut row0 = Vec::new();
    for hyp in [Smooth::Reflection, Smooth::Emission] {
        for (column, target) in columns.iter().enumerate() {
            row0.push(Row0Fit {
                hyp,
                column,
                rms_paper_n: compute::rms_pct(|t| hyp.dolp(N, 0.0, t), target),
                real: compute::fit_real_n(hyp, target),
                complex: compute::fit_complex_n(hyp, target),
            });
        }
    }
    row0
}

/// The best real index of the row-0 fit of `hyp` against `column` (NaN if it was not fitted).
fn fitted_n(row0: &[Row0Fit], hyp: Smooth, column: usize) -> f64 {
    row0.iter()
        .find(|f| f.hyp == hyp && f.column == column)
        .map_or(f64::NAN, |f| f.real.n)
}

/// Fig. 5(b)'s smooth-surface curves at `dolp_angles`: reflection and emission, each at the
/// paper's n and at the n that best fits the paper's model column of row 0.
fn hypothesis_curves(row0: &[Row0Fit], dolp_angles: &[f64]) -> Vec<(String, Vec<f64>)> {
    let fit = |hyp: Smooth, column: usize| fitted_n(row0, hyp, column);
    let mut hypothesis_curves = Vec::new();
    for (label, hyp, n) in [
        (format!("reflection, n = {N}"), Smooth::Reflection, N),
        (
            format!(
                "reflection, n = {:.2} (best fit)",
                fit(Smooth::Reflection, 0)
            ),
            Smooth::Reflection,
            fit(Smooth::Reflection, 0),
        ),
        (format!("emission, n = {N}"), Smooth::Emission, N),
        (
            format!("emission, n = {:.1} (best fit)", fit(Smooth::Emission, 0)),
            Smooth::Emission,
            fit(Smooth::Emission, 0),
        ),
    ] {
        let y = dolp_angles
            .iter()
            .map(|t| hyp.dolp(n, 0.0, t.to_radians()))
            .collect();
        hypothesis_curves.push((label, y));
    }
    hypothesis_curves
}

/// The roughness interpretations tried against Table 1, in the report's order; the first is
/// the primary one. (c) uses `emission_n`, the best emission fit of row 0.
fn interpretations(emission_n: f64) -> [(String, Roughness); 5] {
    [
        (
            "(a) σ in rad + volume term, eq. 6 form [primary]".into(),
            Roughness::SigmaWithVolume(Form::Paper),
        ),
        (
            "(a′) σ in rad + volume term, standard form".into(),
            Roughness::SigmaWithVolume(Form::Standard),
        ),
        (
            "(b) θN in rad at β = θi (Fig. 2 construction) + volume term".into(),
            Roughness::ThetaNWithVolume,
        ),
        (
            "(a₀) σ in rad, no volume term".into(),
            Roughness::SigmaNoVolume,
        ),
        (
            format!("(c) thermal emission (Kirchhoff), σ in rad, n = {emission_n:.1}"),
            Roughness::Emission(emission_n, true),
        ),
    ]
}

/// What the roughness interpretations give.
struct RoughnessPart {
    /// Each interpretation at Table 1's cells, with its RMS against both columns.
    interps: Vec<InterpResult>,
    /// Fig. 4: the primary interpretation's DoLP curves.
    fig4: Vec<Vec<f64>>,
    /// See [`Analysis::no_volume_max_change`].
    no_volume_max_change: f64,
    /// The diagnostics of interpretation (c).
    emission_notes: EmissionNotes,
}

/// Evaluates every interpretation at Table 1's cells (claim 6: agreement with Lawrence/Wolff;
/// claim 5: does roughness lower the DoLP?), the primary one's curves at `dolp_angles` (Fig. 4,
/// Fig. 5(a)), the largest DoLP change without a volume term (claim 5) and the diagnostics of
/// (c); `tick` after each interpretation.
fn roughness_part(
    emission_n: f64,
    dolp_angles: &[f64],
    tick: &mut dyn FnMut(&str),
) -> Result<RoughnessPart, polbrdf::Error> {
    let table_model = TABLE_PAPER_MODEL;
    let table_lawrence = TABLE_PAPER_LAWRENCE;
    let mut interps = Vec::new();
    let mut fig4 = Vec::new();
    let mut no_volume_max_change = 0.0;
    let mut emission_notes = None;
    for (label, how) in interpretations(emission_n) {
        let it = Interpretation::new(how)?;
        let cells = compute::table_cells(&it);
        if let Roughness::Emission(n, true) = how {
            emission_notes = Some(self::emission_notes(n, &it)?);
        }
        if interps.is_empty() {
            fig4 = compute::dolp_curves(&it, dolp_angles);
        }
        if how == Roughness::SigmaNoVolume {
            no_volume_max_change = max_change_from_smooth(&it, dolp_angles);
        }
        interps.push(InterpResult {
            label,
            how,
            rms_model: compute::rms_cells(&cells, &table_model),
            rms_lawrence: compute::rms_cells(&cells, &table_lawrence),
            rel_model: compute::rms_relative(&cells, &table_model),
            rel_lawrence: compute::rms_relative(&cells, &table_lawrence),
            cells,
        });
        tick("roughness interpretation evaluated");
    }
    let emission_notes = emission_notes.ok_or_else(|| {
        polbrdf::Error::InconsistentParameters("interpretation (c) not evaluated".into())
    })?;
    Ok(RoughnessPart {
        interps,
        fig4,
        no_volume_max_change,
        emission_notes,
    })
}

/// `max |DoLP(σ) − DoLP(σ → 0)|` of interpretation `it` over its roughness rows and
/// `dolp_angles` (claim 5: without a volume term roughness leaves the specular DoLP unchanged).
fn max_change_from_smooth(it: &Interpretation, dolp_angles: &[f64]) -> f64 {
    let curves = compute::dolp_curves(it, dolp_angles);
    let mut max_change = 0.0;
    for c in &curves[1..] {
        for (a, b) in c.iter().zip(&curves[0]) {
            max_change = f64::max(max_change, (a - b).abs());
        }
    }
    max_change
}

/// Number of `tick` calls made by [`analyze`].
pub const STEPS: usize = 3 + 5;
