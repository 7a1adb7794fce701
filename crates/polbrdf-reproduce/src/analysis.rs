//! Everything computed for the report, in one place: the figures' data and the numbers that
//! decide each of the paper's claims.

use crate::compute::{self, Fig2, IndexFit, Interpretation, Roughness, Smooth};
use crate::params::*;
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
    /// Diagnostics of interpretation (c): (description, value).
    pub emission_notes: EmissionNotes,
}

/// Why the rough-emission interpretation (c) is not usable with this model: energy balance.
#[derive(Debug, Clone, Copy)]
pub struct EmissionNotes {
    /// Flat-surface reflectance R_F at 20° for the emission index.
    pub r_flat_20: f64,
    /// Directional-hemispherical reflectance of the model at 20°, σ = 0.1 rad, shadowing on.
    pub dhr_20_so: f64,
    /// s- and p-polarized hemispherical reflectance at 80°, σ = 0.3 rad, shadowing off (R_s
    /// exceeds 1: the model does not conserve energy there).
    pub dhr_80_noso: (f64, f64),
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

/// Runs every computation; `tick` is called after each of `STEPS` steps.
pub fn analyze(tick: &mut dyn FnMut(&str)) -> Result<Analysis, polbrdf::Error> {
    let (fig2, spreads, fig2_decreasing, fig2_ordered) = fig2_part()?;
    let crossings = crossings(&fig2);
    tick("Fig. 2 computed");

    let fig3 = compute::fig3()?;
    let fig3_peak =
        fig3.iter().copied().fold(
            (f64::NAN, f64::NEG_INFINITY),
            |a, b| if b.1 > a.1 { b } else { a },
        );
    let dolp_angles = compute::dolp_angles_deg();
    tick("Fig. 3 computed");

    // Row-0 hypotheses.
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
    let fit = |hyp: Smooth, column: usize| {
        row0.iter()
            .find(|f| f.hyp == hyp && f.column == column)
            .map_or(f64::NAN, |f| f.real.n)
    };
    let emission_n = fit(Smooth::Emission, 1);
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
    tick("Table 1 row 0 fitted");

    // Roughness interpretations.
    let table_model = TABLE_PAPER_MODEL;
    let table_lawrence = TABLE_PAPER_LAWRENCE;
    let kinds: [(String, Roughness); 5] = [
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
    ];
    let mut interps = Vec::new();
    let mut fig4 = Vec::new();
    let mut no_volume_max_change = 0.0;
    for (label, how) in kinds {
        let it = Interpretation::new(how)?;
        let cells = compute::table_cells(&it);
        if interps.is_empty() {
            fig4 = compute::dolp_curves(&it, &dolp_angles);
        }
        if how == Roughness::SigmaNoVolume {
            let curves = compute::dolp_curves(&it, &dolp_angles);
            for c in &curves[1..] {
                for (a, b) in c.iter().zip(&curves[0]) {
                    no_volume_max_change = f64::max(no_volume_max_change, (a - b).abs());
                }
            }
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

    let emission_notes = {
        let q = compute::Quadrature::new();
        let build = |sigma: f64, shadowing: bool| {
            let mut spec = polbrdf::MaterialSpec::new(emission_n, sigma.to_degrees());
            spec.form = Form::Standard;
            spec.shadowing = shadowing;
            spec.tau_deg = TAU_DEG;
            spec.omega_deg = OMEGA_DEG;
            spec.build()
        };
        let (rs, rp) = compute::fresnel_rs_rp(emission_n, 0.0, 20f64.to_radians());
        let (a1, b1) = q.hemispherical_rs_rp(&build(0.1, true)?, 20f64.to_radians());
        let (a2, b2) = q.hemispherical_rs_rp(&build(0.3, false)?, 80f64.to_radians());
        EmissionNotes {
            r_flat_20: 0.5 * (rs + rp),
            dhr_20_so: 0.5 * (a1 + b1),
            dhr_80_noso: (a2, b2),
        }
    };

    Ok(Analysis {
        fig2,
        crossings,
        emission_notes,
        spreads,
        fig2_decreasing,
        fig2_ordered,
        fig3,
        fig3_peak,
        dolp_angles,
        fig4,
        interps,
        no_volume_max_change,
        row0,
        emission_n,
        hypothesis_curves,
    })
}

/// Number of `tick` calls made by [`analyze`].
pub const STEPS: usize = 3 + 5;
