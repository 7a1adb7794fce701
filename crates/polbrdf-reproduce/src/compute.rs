//! The numbers behind every figure, table and claim. Every grid goes through the core crate's
//! batch engine ([`Engine`]: the same functions as [`Material::evaluate`] and
//! [`Material::evaluate_angles`]) or, for the thermal-emission interpretation (c), through the
//! core's Kirchhoff emissivity ([`emissivities`]); the only formulas written here are the
//! Fresnel-level hypotheses for Table 1's smooth row, built on [`RefractiveIndex::amplitudes`].

use crate::params::*;
use polbrdf::analysis::emission::{emissivities, Emissivity};
use polbrdf::{
    AngleVariables, Engine, Form, GeometryBatch, Material, MaterialSpec, Mueller, RefractiveIndex,
    Result as CoreResult,
};
use std::f64::consts::{FRAC_PI_2, PI};

/// A material with the paper's n, τ, Ω and the given width of D and volume term.
pub fn material(
    form: Form,
    sigma_deg: f64,
    rho_d: f64,
    rho_v: f64,
    shadowing: bool,
) -> CoreResult<Material> {
    let mut spec = MaterialSpec::new(N, sigma_deg);
    spec.form = form;
    spec.rho_d = rho_d;
    spec.rho_v = rho_v;
    spec.shadowing = shadowing;
    spec.tau_deg = TAU_DEG;
    spec.omega_deg = OMEGA_DEG;
    spec.build()
}

/// The material of interpretation (c) (thermal emission) at roughness `sigma` (σ of D in
/// radians): real index `n`, standard form (the `paper` form has no emissivity: its
/// hemispherical integrals diverge), no volume term, the paper's τ and Ω, shadowing as given.
pub fn emission_material(n: f64, sigma: f64, shadowing: bool) -> CoreResult<Material> {
    let mut spec = MaterialSpec::new(n, sigma.to_degrees());
    spec.shadowing = shadowing;
    spec.form = Form::Standard;
    spec.tau_deg = TAU_DEG;
    spec.omega_deg = OMEGA_DEG;
    spec.build()
}

/// `lo, lo+step, …` up to and including `hi` (to rounding).
pub fn grid(lo: f64, hi: f64, step: f64) -> Vec<f64> {
    let n = ((hi - lo) / step + 1e-9).floor() as usize;
    // Rounded to 1e-9 so that CSV files show 0.3, not 0.30000000000000004.
    (0..=n)
        .map(|i| ((lo + i as f64 * step) * 1e9).round() / 1e9)
        .collect()
}

// ---------------------------------------------------------------------------------------------
// Fig. 2

/// Fig. 2: the scalar BRDF (eq. 6) against θN at in-plane specular geometry.
#[derive(Debug, Clone)]
pub struct Fig2 {
    /// Incidence angles θi = θr of the curves, degrees.
    pub thetas_deg: Vec<f64>,
    /// θN values, degrees.
    pub theta_n_deg: Vec<f64>,
    /// `brdf[i][j]`: f at `thetas_deg[i]`, `theta_n_deg[j]`, shadowing on (sr⁻¹).
    pub brdf: Vec<Vec<f64>>,
    /// The same with shadowing switched off.
    pub brdf_no_shadow: Vec<Vec<f64>>,
    /// The hemispherical normalization constant `a` of D (sr⁻¹).
    pub a: f64,
    /// `b = 1/σ²` (rad⁻²).
    pub b: f64,
}

/// Computes Fig. 2.
pub fn fig2() -> CoreResult<Fig2> {
    let on = material(Form::Paper, FIG2_SIGMA_DEG, 0.0, 0.0, true)?;
    let off = material(Form::Paper, FIG2_SIGMA_DEG, 0.0, 0.0, false)?;
    let theta_n_deg = grid(
        FIG2_THETA_N_STEP_DEG,
        FIG2_THETA_N_MAX_DEG,
        FIG2_THETA_N_STEP_DEG,
    );
    let curve = |m: &Material, theta_deg: f64| -> CoreResult<Vec<f64>> {
        let vars: Vec<AngleVariables> = theta_n_deg
            .iter()
            .map(|&tn| AngleVariables::in_plane_specular(theta_deg.to_radians(), tn.to_radians()))
            .collect();
        Ok(Engine::new(m)
            .mueller_of_angles(&vars)?
            .iter()
            .map(|f| f[0])
            .collect())
    };
    Ok(Fig2 {
        thetas_deg: FIG2_THETAS_DEG.to_vec(),
        brdf: FIG2_THETAS_DEG
            .iter()
            .map(|&t| curve(&on, t))
            .collect::<CoreResult<_>>()?,
        brdf_no_shadow: FIG2_THETAS_DEG
            .iter()
            .map(|&t| curve(&off, t))
            .collect::<CoreResult<_>>()?,
        theta_n_deg,
        a: on.distribution().a(),
        b: on.distribution().b(),
    })
}

// ---------------------------------------------------------------------------------------------
// Fresnel-level quantities

/// `(Rs, Rp)` of a flat interface with index `n + ik` at incidence `theta` (rad).
pub fn fresnel_rs_rp(n: f64, k: f64, theta: f64) -> (f64, f64) {
    match RefractiveIndex::new(n, k) {
        Ok(ix) => {
            let f = ix.amplitudes(theta);
            (f.reflectance_s(), f.reflectance_p())
        }
        Err(_) => (f64::NAN, f64::NAN),
    }
}

/// How a smooth surface could have produced Table 1's row 0.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Smooth {
    /// DoLP of specularly reflected unpolarized light, `(Rs − Rp)/(Rs + Rp)` (what the model
    /// gives at specular geometry with no volume term).
    Reflection,
    /// DoLP of thermal emission (Kirchhoff: ε = 1 − R), `(Rs − Rp)/(2 − Rs − Rp)`, the subject
    /// of the paper's ref. \[9\] (Wolff, Lundberg & Tang 1998).
    Emission,
}

impl Smooth {
    /// DoLP (fraction) of a flat surface of index `n + ik` at `theta` (rad).
    pub fn dolp(self, n: f64, k: f64, theta: f64) -> f64 {
        let (rs, rp) = fresnel_rs_rp(n, k, theta);
        match self {
            Smooth::Reflection => (rs - rp).abs() / (rs + rp),
            Smooth::Emission => (rs - rp).abs() / (2.0 - rs - rp),
        }
    }

    /// Short name.
    pub fn name(self) -> &'static str {
        match self {
            Smooth::Reflection => "reflection",
            Smooth::Emission => "thermal emission",
        }
    }
}

/// RMS difference (percentage points) between `f(θ)·100` at Table 1's angles and `target`.
pub fn rms_pct(f: impl Fn(f64) -> f64, target: &[f64; 5]) -> f64 {
    let s: f64 = TABLE_ANGLES_DEG
        .iter()
        .zip(target)
        .map(|(&t, &y)| {
            let d = 100.0 * f(t.to_radians()) - y;
            d * d
        })
        .sum();
    (s / 5.0).sqrt()
}

/// Result of an index fit to Table 1's row 0.
#[derive(Debug, Clone, Copy)]
pub struct IndexFit {
    /// Fitted n.
    pub n: f64,
    /// Fitted k (0 for the real-index scan).
    pub k: f64,
    /// RMS difference at the optimum, percentage points.
    pub rms: f64,
}

/// 1-D least-squares scan for the real index n in [SCAN_N_MIN, SCAN_N_MAX] (log grid of 4000
/// points, then golden-section refinement) that best reproduces `target` under `hyp`.
pub fn fit_real_n(hyp: Smooth, target: &[f64; 5]) -> IndexFit {
    let cost = |n: f64| {
        let r = rms_pct(|t| hyp.dolp(n, 0.0, t), target);
        if r.is_finite() {
            r
        } else {
            f64::INFINITY
        }
    };
    let m = 4000;
    let (l0, l1) = (SCAN_N_MIN.ln(), SCAN_N_MAX.ln());
    let ns: Vec<f64> = (0..m)
        .map(|i| (l0 + (l1 - l0) * i as f64 / (m - 1) as f64).exp())
        .collect();
    let (ib, _) =
        ns.iter()
            .map(|&n| cost(n))
            .enumerate()
            .fold(
                (0, f64::INFINITY),
                |acc, (i, c)| {
                    if c < acc.1 {
                        (i, c)
                    } else {
                        acc
                    }
                },
            );
    let lo = ns[ib.saturating_sub(1)];
    let hi = ns[(ib + 1).min(m - 1)];
    let n = golden(cost, lo, hi);
    IndexFit {
        n,
        k: 0.0,
        rms: cost(n),
    }
}

/// 2-D grid scan for the complex index n + ik (n ∈ [0.05, 20], k ∈ [0, 20], step 0.05, then a
/// 0.002 grid around the best cell). Shows how little row 0 constrains the material.
pub fn fit_complex_n(hyp: Smooth, target: &[f64; 5]) -> IndexFit {
    let cost = |n: f64, k: f64| {
        let r = rms_pct(|t| hyp.dolp(n, k, t), target);
        if r.is_finite() {
            r
        } else {
            f64::INFINITY
        }
    };
    let scan = |best: IndexFit, n0: f64, k0: f64, step: f64, count_n: usize, count_k: usize| {
        let mut b = best;
        for i in 0..count_n {
            let n = n0 + step * i as f64;
            if n <= 0.0 {
                continue;
            }
            for j in 0..count_k {
                let k = k0 + step * j as f64;
                if k < 0.0 {
                    continue;
                }
                let c = cost(n, k);
                if c < b.rms {
                    b = IndexFit { n, k, rms: c };
                }
            }
        }
        b
    };
    let none = IndexFit {
        n: f64::NAN,
        k: f64::NAN,
        rms: f64::INFINITY,
    };
    let coarse = scan(none, 0.05, 0.0, 0.05, 400, 401);
    scan(coarse, coarse.n - 0.05, coarse.k - 0.05, 0.002, 51, 51)
}

/// Golden-section minimization of a unimodal `f` on `[a, b]`.
fn golden(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    let g = (5f64.sqrt() - 1.0) / 2.0;
    let mut c = b - g * (b - a);
    let mut d = a + g * (b - a);
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..100 {
        if (b - a).abs() < 1e-10 * (a.abs() + b.abs()) {
            break;
        }
        if fc < fd {
            b = d;
            d = c;
            fd = fc;
            c = b - g * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + g * (b - a);
            fd = f(d);
        }
    }
    0.5 * (a + b)
}

// ---------------------------------------------------------------------------------------------
// Roughness interpretations for Fig. 4 / Table 1

/// What "roughness" (0 … 0.5) in Fig. 4 and Table 1 is taken to mean.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Roughness {
    /// (a) σ of D in radians (b = 1/σ²), specular geometry, with the fixed volume term
    /// (ρ_D, ρ_V); roughness 0 is the σ → 0 limit (pure Fresnel). The surface-term form is the
    /// field. **Primary** with [`Form::Paper`].
    SigmaWithVolume(Form),
    /// (b) θN in radians as a free variable at β = θi (the paper's Fig. 2 construction, eq. 6,
    /// σ = 15°) with the same volume term.
    ThetaNWithVolume,
    /// (a) without a volume term: σ in radians, specular geometry — shows that roughness alone
    /// does not change DoLP in this model.
    SigmaNoVolume,
    /// (c) thermal emission of the rough surface by Kirchhoff's law, ε_s,p = 1 − (directional-
    /// hemispherical reflectance of the model for s, p input), σ = roughness in radians,
    /// standard form, no volume term, index `n` (real); shadowing on when the flag is true
    /// ([`emission_material`]). Every value σ > 0 is the core's emissivity ([`emissivities`],
    /// route A) and its DoLP [`Emissivity::dolp`]; roughness 0 is the σ → 0 limit, the Fresnel
    /// emission DoLP [`Smooth::Emission`].
    Emission(f64, bool),
}

/// Evaluates DoLP (fraction) for unpolarized light (or emission) at `theta` (rad) for
/// roughness `r` under interpretation `how`.
pub struct Interpretation {
    how: Roughness,
    /// One material per roughness value (None for the σ → 0 limit).
    materials: Vec<(f64, Option<Material>)>,
    smooth: Material,
}

impl Interpretation {
    /// Prepares the materials for the roughness values in `ROUGHNESS`.
    pub fn new(how: Roughness) -> CoreResult<Self> {
        let mut materials = Vec::new();
        for &r in &ROUGHNESS {
            let m = match how {
                Roughness::SigmaWithVolume(form) if r > 0.0 => {
                    Some(material(form, r.to_degrees(), RHO_D, RHO_V, true)?)
                }
                Roughness::SigmaNoVolume if r > 0.0 => {
                    Some(material(Form::Paper, r.to_degrees(), 0.0, 0.0, true)?)
                }
                Roughness::Emission(n, shadowing) if r > 0.0 => {
                    Some(emission_material(n, r, shadowing)?)
                }
                Roughness::ThetaNWithVolume => {
                    Some(material(Form::Paper, FIG2_SIGMA_DEG, RHO_D, RHO_V, true)?)
                }
                _ => None,
            };
            materials.push((r, m));
        }
        Ok(Self {
            how,
            materials,
            smooth: material(Form::Paper, SMOOTH_SIGMA_DEG, 0.0, 0.0, true)?,
        })
    }

    /// The interpretation.
    pub fn how(&self) -> Roughness {
        self.how
    }

    /// DoLP (fraction) at roughness index `ri` (into `ROUGHNESS`) and angle `theta` (rad).
    pub fn dolp(&self, ri: usize, theta: f64) -> f64 {
        self.dolp_at(ri, &[theta])[0]
    }

    /// The material of roughness index `ri` (`None` for the σ → 0 row of (a), (a₀) and (c)).
    pub fn material(&self, ri: usize) -> Option<&Material> {
        self.materials[ri].1.as_ref()
    }

    /// For interpretation (c) at σ > 0: the core's Kirchhoff emissivity (both routes) at
    /// roughness index `ri` and each view angle of `thetas` (rad, in `[0, π/2)`), one batched
    /// call. `None` for the σ → 0 row (the Fresnel limit) and for the other interpretations.
    ///
    /// # Errors
    /// The core's, for an angle outside `[0, π/2)`.
    pub fn emissivities_at(
        &self,
        ri: usize,
        thetas: &[f64],
    ) -> Option<CoreResult<Vec<Emissivity>>> {
        match (self.how, &self.materials[ri].1) {
            (Roughness::Emission(..), Some(m)) => Some(emissivities(m, thetas)),
            _ => None,
        }
    }

    /// DoLP (fraction) at roughness index `ri` and each angle of `thetas` (rad), through the
    /// engine (for (c), the core's emissivity; NaN at angles outside `[0, π/2)`).
    pub fn dolp_at(&self, ri: usize, thetas: &[f64]) -> Vec<f64> {
        let (r, ref m) = self.materials[ri];
        match (self.how, m) {
            (Roughness::Emission(n, _), None) => thetas
                .iter()
                .map(|&t| Smooth::Emission.dolp(n, 0.0, t))
                .collect(),
            (Roughness::Emission(_, _), Some(m)) => emission_dolp(m, thetas),
            (Roughness::ThetaNWithVolume, Some(m)) => {
                let vars: Vec<AngleVariables> = thetas
                    .iter()
                    .map(|&t| AngleVariables::in_plane_specular(t, r))
                    .collect();
                Engine::new(m)
                    .mueller_of_angles(&vars)
                    .expect("no per-element index")
                    .iter()
                    .map(|f| Mueller::from_row_major(f).dolp_unpolarized())
                    .collect()
            }
            (_, Some(m)) => specular_dolp(m, thetas),
            (_, None) => specular_dolp(&self.smooth, thetas),
        }
    }
}

/// The DoLP of the model at in-plane specular geometry θr = θi = θ, at each θ (rad; 0 at or
/// beyond 90°), through the engine.
pub fn specular_dolp(m: &Material, thetas: &[f64]) -> Vec<f64> {
    let t: Vec<f64> = thetas.iter().map(|t| t.clamp(0.0, PI)).collect();
    let zeros = vec![0.0; t.len()];
    let pis = vec![PI; t.len()];
    let (mut brdf, mut dolp) = (vec![0.0; t.len()], vec![0.0; t.len()]);
    let ok = GeometryBatch::new(&t, &zeros, &t, &pis)
        .and_then(|b| Engine::new(m).brdf_dolp_into(&b, &mut brdf, &mut dolp));
    match ok {
        Ok(()) => dolp,
        Err(_) => vec![f64::NAN; t.len()],
    }
}

/// The DoLP `sqrt(ε1² + ε2²)/ε0` of the thermal emission of `m` toward each view angle of
/// `thetas` (rad), from the core's Kirchhoff emissivity ([`emissivities`], route A; one batched
/// call); NaN at angles outside `[0, π/2)`, where no direction is viewed.
pub fn emission_dolp(m: &Material, thetas: &[f64]) -> Vec<f64> {
    let inside = |t: f64| (0.0..FRAC_PI_2).contains(&t);
    let viewed: Vec<f64> = thetas.iter().copied().filter(|&t| inside(t)).collect();
    let Ok(e) = emissivities(m, &viewed) else {
        return vec![f64::NAN; thetas.len()];
    };
    let mut e = e.iter();
    thetas
        .iter()
        .map(|&t| {
            if inside(t) {
                e.next().map_or(f64::NAN, Emissivity::dolp)
            } else {
                f64::NAN
            }
        })
        .collect()
}

// ---------------------------------------------------------------------------------------------
// Fig. 3, Fig. 4, Table 1

/// The angles of the DoLP curves, degrees: 0°, 0.1°, …, 89.9°, plus Brewster's angle
/// atan(n) inserted in order (so the curve's maximum is sampled exactly).
pub fn dolp_angles_deg() -> Vec<f64> {
    let mut t = grid(0.0, DOLP_MAX_DEG, DOLP_STEP_DEG);
    let b = N.atan().to_degrees();
    let at = t.partition_point(|&x| x < b);
    if t.get(at) != Some(&b) {
        t.insert(at, b);
    }
    t
}

/// Fig. 3: DoLP of a smooth surface (no volume term) at specular geometry, unpolarized input:
/// `(θ in degrees, DoLP)`.
pub fn fig3() -> CoreResult<Vec<(f64, f64)>> {
    let m = material(Form::Paper, SMOOTH_SIGMA_DEG, 0.0, 0.0, true)?;
    let angles = dolp_angles_deg();
    let rad: Vec<f64> = angles.iter().map(|t| t.to_radians()).collect();
    Ok(angles.into_iter().zip(specular_dolp(&m, &rad)).collect())
}

/// DoLP curves (fractions) of an interpretation, one per roughness value, at `angles_deg`.
pub fn dolp_curves(it: &Interpretation, angles_deg: &[f64]) -> Vec<Vec<f64>> {
    let rad: Vec<f64> = angles_deg.iter().map(|t| t.to_radians()).collect();
    (0..ROUGHNESS.len())
        .map(|ri| it.dolp_at(ri, &rad))
        .collect()
}

/// DoLP in % at Table 1's cells: `[row][column]`.
pub fn table_cells(it: &Interpretation) -> [[f64; 5]; 6] {
    let mut out = [[0.0; 5]; 6];
    let rad: Vec<f64> = TABLE_ANGLES_DEG.iter().map(|t| t.to_radians()).collect();
    for (ri, row) in out.iter_mut().enumerate() {
        for (cell, d) in row.iter_mut().zip(it.dolp_at(ri, &rad)) {
            *cell = 100.0 * d;
        }
    }
    out
}

/// RMS difference over all cells (percentage points).
pub fn rms_cells(a: &[[f64; 5]; 6], b: &[[f64; 5]; 6]) -> f64 {
    let mut s = 0.0;
    for (ra, rb) in a.iter().zip(b) {
        for (x, y) in ra.iter().zip(rb) {
            s += (x - y) * (x - y);
        }
    }
    (s / 30.0).sqrt()
}

/// RMS difference (percentage points of the row-0 value) of the *relative* roughness effect,
/// `DoLP(r)/DoLP(0)`, over rows 0.1 … 0.5: compares how roughness changes DoLP independently
/// of whether the smooth values agree.
pub fn rms_relative(a: &[[f64; 5]; 6], b: &[[f64; 5]; 6]) -> f64 {
    let mut s = 0.0;
    for r in 1..6 {
        for c in 0..5 {
            let d = 100.0 * (a[r][c] / a[0][c] - b[r][c] / b[0][c]);
            s += d * d;
        }
    }
    (s / 25.0).sqrt()
}
