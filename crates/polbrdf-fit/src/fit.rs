//! The general fit: any subset of the material parameters against any mix of measured BRDF,
//! DoLP and Mueller entries, by Levenberg–Marquardt, with covariance and χ².

use crate::error::FitError;
use crate::lm::{self, cholesky_solve, LmOptions};
use crate::params::Param;
use crate::zbs::{self, ZbsFit, ZbsPoint};
use polbrdf::{AngleVariables, Evaluation, Geometry, Material, MaterialSpec};
use rayon::prelude::*;

/// A measurable quantity.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Observable {
    /// Scalar BRDF `f = F00` (sr⁻¹).
    Brdf,
    /// DoLP for unpolarized illumination (eq. 13).
    Dolp,
    /// Mueller-matrix BRDF entry `F_ij` (sr⁻¹, psps basis).
    Mueller(usize, usize),
}

impl Observable {
    /// From a column name: `brdf`, `dolp`, `m00` … `m33`.
    pub fn parse(name: &str) -> Option<Self> {
        match name {
            "brdf" => Some(Observable::Brdf),
            "dolp" => Some(Observable::Dolp),
            _ => {
                let d: Vec<usize> = name
                    .strip_prefix('m')?
                    .chars()
                    .map(|c| c.to_digit(10).map(|d| d as usize))
                    .collect::<Option<_>>()?;
                match d[..] {
                    [i, j] if i < 4 && j < 4 => Some(Observable::Mueller(i, j)),
                    _ => None,
                }
            }
        }
    }

    /// The column name.
    pub fn name(&self) -> String {
        match self {
            Observable::Brdf => "brdf".into(),
            Observable::Dolp => "dolp".into(),
            Observable::Mueller(i, j) => format!("m{i}{j}"),
        }
    }

    /// The model's value of this quantity.
    pub fn of(&self, e: &Evaluation) -> f64 {
        match *self {
            Observable::Brdf => e.brdf(),
            Observable::Dolp => e.dolp(),
            Observable::Mueller(i, j) => e.pbrdf.0[i][j],
        }
    }
}

/// One measured value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measurement {
    /// Where it was measured.
    pub geometry: Geometry,
    /// What was measured.
    pub observable: Observable,
    /// The value.
    pub value: f64,
    /// Its 1-σ uncertainty, if known (> 0).
    pub sigma: Option<f64>,
}

/// Settings of [`fit`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitOptions {
    /// Extra starts, scattered around the initial values (factor up to 2 each way), besides the
    /// initial values and the zero-bistatic start. The best result is kept.
    pub extra_starts: usize,
    /// Seed of the scatter.
    pub seed: u64,
    /// Stopping rules.
    pub lm: LmOptions,
}

impl Default for FitOptions {
    fn default() -> Self {
        Self {
            extra_starts: 2,
            seed: 1,
            lm: LmOptions::default(),
        }
    }
}

/// One measurement beside the fitted model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Residual {
    /// Index into the measurements given to [`fit`].
    pub index: usize,
    /// The model's value.
    pub model: f64,
    /// The measured value.
    pub data: f64,
    /// The uncertainty used (given, or estimated from the residuals).
    pub sigma: f64,
}

/// The outcome of a fit.
#[derive(Debug, Clone, PartialEq)]
pub struct FitResult {
    /// Free parameters, in the order given.
    pub params: Vec<Param>,
    /// Their fitted values.
    pub values: Vec<f64>,
    /// Their standard errors, `sqrt(diag(covariance))`.
    pub stderr: Vec<f64>,
    /// Covariance matrix (row-major, in the order of `params`).
    pub covariance: Vec<Vec<f64>>,
    /// Correlation matrix.
    pub correlation: Vec<Vec<f64>>,
    /// χ² = Σ ((model − data)/σ)², with σ = 1 where no uncertainty was given.
    pub chi2: f64,
    /// Degrees of freedom: measurements − free parameters.
    pub dof: usize,
    /// χ²/dof.
    pub reduced_chi2: f64,
    /// True when the uncertainties were estimated from the scatter of the residuals (some
    /// measurement had no σ): covariance scaled by χ²/dof.
    pub scaled_by_residuals: bool,
    /// Whether the minimizer met a convergence test.
    pub converged: bool,
    /// Minimizer steps of the best start.
    pub iterations: usize,
    /// How it stopped, in words.
    pub message: String,
    /// Number of starts tried, and how many of them reached the best χ² (to 1e-6): fewer than
    /// all suggests several minima.
    pub starts: (usize, usize),
    /// The zero-bistatic inversion used for a start, when the data allowed one.
    pub zero_bistatic: Option<ZbsFit>,
    /// The fitted material.
    pub spec: MaterialSpec,
    /// Every measurement beside the model.
    pub residuals: Vec<Residual>,
}

/// The prepared problem: unique geometries with their angle variables, and the measurements
/// grouped by geometry in blocks for parallel evaluation.
struct Problem<'a> {
    base: MaterialSpec,
    free: &'a [Param],
    angles: Vec<Option<AngleVariables>>,
    /// Per measurement: (geometry index, observable, value, weight 1/σ).
    rows: Vec<(usize, Observable, f64, f64)>,
    /// Measurement index ranges of consecutive blocks of geometries.
    blocks: Vec<std::ops::Range<usize>>,
}

const BLOCK: usize = 256;

impl Problem<'_> {
    fn spec_at(&self, x: &[f64]) -> MaterialSpec {
        let mut spec = self.base.clone();
        for (p, v) in self.free.iter().zip(x) {
            p.set(&mut spec, *v);
        }
        spec
    }

    /// Weighted residuals `(model − data)/σ` at natural parameter values `x`.
    fn residuals(&self, x: &[f64], out: &mut [f64]) -> bool {
        let Ok(material) = self.spec_at(x).build() else {
            return false;
        };
        self.residuals_of(&material, out);
        out.iter().all(|v| v.is_finite())
    }

    fn residuals_of(&self, material: &Material, out: &mut [f64]) {
        let mut slices = Vec::with_capacity(self.blocks.len());
        let mut rest = out;
        for b in &self.blocks {
            let (head, tail) = rest.split_at_mut(b.len());
            slices.push(head);
            rest = tail;
        }
        slices
            .into_par_iter()
            .zip(self.blocks.par_iter())
            .for_each(|(out, range)| {
                let mut last = usize::MAX;
                let mut e = Evaluation::zero();
                for (o, &(g, obs, value, w)) in out.iter_mut().zip(&self.rows[range.clone()]) {
                    if g != last {
                        e = match &self.angles[g] {
                            Some(v) => material.evaluate_angles(v),
                            None => Evaluation::zero(),
                        };
                        last = g;
                    }
                    *o = (obs.of(&e) - value) * w;
                }
            });
    }
}

fn lcg(state: &mut u64) -> f64 {
    *state = state
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    ((*state >> 11) as f64) / ((1u64 << 53) as f64)
}

/// Fits the `free` parameters of `base` to `data`.
///
/// Parameters are kept in their domain by fitting `ln x` (strictly positive ones) or `√x`
/// (non-negative ones); the covariance is computed in the natural parameters from a
/// central-difference Jacobian at the solution.
///
/// # Errors
/// [`FitError::TooFewPoints`] unless there are more measurements than free parameters;
/// [`FitError::Unidentifiable`] when the data cannot determine some parameter;
/// [`FitError::Model`] if `base` is invalid.
pub fn fit(
    base: &MaterialSpec,
    free: &[Param],
    data: &[Measurement],
    opts: &FitOptions,
) -> Result<FitResult, FitError> {
    base.build()?;
    if free.is_empty() {
        return Err(FitError::BadParameterList("no free parameter".into()));
    }
    let p = free.len();
    let m = data.len();
    if m <= p {
        return Err(FitError::TooFewPoints {
            measurements: m,
            parameters: p,
        });
    }
    // Group consecutive measurements at the same geometry.
    let mut angles = Vec::new();
    let mut geoms: Vec<Geometry> = Vec::new();
    let mut rows = Vec::with_capacity(m);
    for d in data {
        if geoms.last() != Some(&d.geometry) {
            geoms.push(d.geometry);
            angles.push(d.geometry.angle_variables());
        }
        rows.push((
            geoms.len() - 1,
            d.observable,
            d.value,
            d.sigma.map_or(1.0, |s| 1.0 / s),
        ));
    }
    let mut blocks = Vec::new();
    let mut start = 0;
    while start < m {
        let g0 = rows[start].0;
        let mut end = start;
        while end < m && rows[end].0 < g0 + BLOCK {
            end += 1;
        }
        blocks.push(start..end);
        start = end;
    }
    let problem = Problem {
        base: base.clone(),
        free,
        angles,
        rows,
        blocks,
    };

    // Start values.
    let initial: Vec<f64> = free
        .iter()
        .map(|p| {
            let v = p.value(base)?;
            Ok(if !p.strictly_positive() && v == 0.0 {
                p.nonzero_start()
            } else {
                v
            })
        })
        .collect::<Result<_, FitError>>()?;
    let mut starts = vec![initial.clone()];
    let zero_bistatic = zero_bistatic_start(base, free, data);
    if let Some(z) = &zero_bistatic {
        let mut s = initial.clone();
        for (k, param) in free.iter().enumerate() {
            match param {
                Param::B => s[k] = z.b,
                Param::SigmaDeg => s[k] = z.b.sqrt().recip().to_degrees(),
                Param::A => s[k] = z.a,
                _ => {}
            }
        }
        if s != initial {
            starts.push(s);
        }
    }
    let mut seed = opts.seed.wrapping_mul(0x9E3779B97F4A7C15) | 1;
    for _ in 0..opts.extra_starts {
        starts.push(
            initial
                .iter()
                .map(|v| v * 2f64.powf(2.0 * lcg(&mut seed) - 1.0))
                .collect(),
        );
    }

    // Minimize from every start (in parallel) in the transformed coordinates.
    let to_x = |u: &[f64]| -> Vec<f64> {
        free.iter()
            .zip(u)
            .map(|(p, u)| p.from_internal(*u))
            .collect()
    };
    let f_u = |u: &[f64], r: &mut [f64]| problem.residuals(&to_x(u), r);
    let reports: Vec<lm::LmReport> = starts
        .par_iter()
        .map(|s| {
            let u0: Vec<f64> = free.iter().zip(s).map(|(p, x)| p.to_internal(*x)).collect();
            lm::minimize(&f_u, &u0, m, &opts.lm)
        })
        .collect();
    let best = reports
        .iter()
        .filter(|r| r.chi2.is_finite())
        .min_by(|a, b| a.chi2.total_cmp(&b.chi2))
        .cloned()
        .ok_or_else(|| {
            FitError::Model(polbrdf::Error::InconsistentParameters(
                "the model could not be evaluated from any start".into(),
            ))
        })?;
    let agreeing = reports
        .iter()
        .filter(|r| r.chi2 <= best.chi2 * (1.0 + 1e-6) + 1e-300)
        .count();
    let x = to_x(&best.u);

    // Covariance in the natural parameters.
    let jac = natural_jacobian(&problem, &x, m);
    let (a, _) = lm::normal_equations(&jac, &vec![0.0; m]);
    check_identifiable(free, &a, &x, &problem)?;
    let scaled_by_residuals = data.iter().any(|d| d.sigma.is_none());
    let dof = m - p;
    let reduced_chi2 = best.chi2 / dof as f64;
    let scale = if scaled_by_residuals {
        reduced_chi2
    } else {
        1.0
    };
    // Columns of (JᵀJ)⁻¹; the matrix is symmetric, so they are also its rows.
    let covariance: Vec<Vec<f64>> = (0..p)
        .map(|j| {
            let e: Vec<f64> = (0..p).map(|i| f64::from(u8::from(i == j))).collect();
            cholesky_solve(&a, &e)
                .map(|col| col.into_iter().map(|v| v * scale).collect())
                .ok_or_else(|| unidentifiable_all(free))
        })
        .collect::<Result<_, _>>()?;
    let stderr: Vec<f64> = (0..p).map(|i| covariance[i][i].max(0.0).sqrt()).collect();
    let correlation = (0..p)
        .map(|i| {
            (0..p)
                .map(|j| covariance[i][j] / (stderr[i] * stderr[j]).max(f64::MIN_POSITIVE))
                .collect()
        })
        .collect();

    let spec = problem.spec_at(&x);
    let material = spec.build()?;
    let sigma_scale = scale.sqrt();
    let residuals = data
        .iter()
        .enumerate()
        .map(|(index, d)| Residual {
            index,
            model: d.observable.of(&material.evaluate(&d.geometry)),
            data: d.value,
            sigma: d.sigma.unwrap_or(sigma_scale),
        })
        .collect();
    Ok(FitResult {
        params: free.to_vec(),
        values: x,
        stderr,
        covariance,
        correlation,
        chi2: best.chi2,
        dof,
        reduced_chi2,
        scaled_by_residuals,
        converged: best.converged,
        iterations: best.iterations,
        message: best.message,
        starts: (starts.len(), agreeing),
        zero_bistatic,
        spec,
        residuals,
    })
}

/// Jacobian of the weighted residuals with respect to the natural parameters: central
/// differences with relative steps 1e-6 (forward where a non-negative parameter sits at 0).
fn natural_jacobian(problem: &Problem<'_>, x: &[f64], m: usize) -> Vec<Vec<f64>> {
    let mut plus = vec![0.0; m];
    let mut minus = vec![0.0; m];
    let mut xp = x.to_vec();
    (0..x.len())
        .map(|j| {
            let h = if x[j] != 0.0 { 1e-6 * x[j].abs() } else { 1e-9 };
            xp[j] = x[j] + h;
            problem.residuals(&xp, &mut plus);
            let central = x[j] - h > 0.0;
            let step = if central {
                xp[j] = x[j] - h;
                problem.residuals(&xp, &mut minus);
                2.0 * h
            } else {
                problem.residuals(x, &mut minus);
                h
            };
            xp[j] = x[j];
            plus.iter()
                .zip(&minus)
                .map(|(a, b)| (a - b) / step)
                .collect()
        })
        .collect()
}

fn unidentifiable_all(free: &[Param]) -> FitError {
    FitError::Unidentifiable(
        free.iter()
            .map(|p| format!("`{}`", p.name()))
            .collect::<Vec<_>>()
            .join(", "),
    )
}

/// Refuses a fit whose normal matrix is (nearly) singular: a parameter without sensitivity, or
/// a combination of parameters the data cannot separate. Names the parameters involved.
fn check_identifiable(
    free: &[Param],
    a: &[f64],
    x: &[f64],
    problem: &Problem<'_>,
) -> Result<(), FitError> {
    let p = free.len();
    // Sensitivity of the residual vector to a 1 % change of each parameter, against the size of
    // the weighted data.
    let data_norm = problem
        .rows
        .iter()
        .map(|&(_, _, v, w)| (v * w) * (v * w))
        .sum::<f64>()
        .sqrt()
        .max(f64::MIN_POSITIVE);
    let dead: Vec<String> = (0..p)
        .filter(|&j| a[j * p + j].sqrt() * x[j].abs().max(1e-12) < 1e-9 * data_norm)
        .map(|j| format!("`{}`", free[j].name()))
        .collect();
    if !dead.is_empty() {
        return Err(FitError::Unidentifiable(dead.join(", ")));
    }
    // Equilibrated normal matrix: a correlation matrix of the linearized problem.
    let d: Vec<f64> = (0..p).map(|j| a[j * p + j].sqrt()).collect();
    let s: Vec<f64> = (0..p * p).map(|k| a[k] / (d[k / p] * d[k % p])).collect();
    let (values, vectors) = polbrdf::linalg::symmetric_eigen_dyn(&s, p);
    for (k, &lambda) in values.iter().enumerate() {
        if lambda < 1e-12 {
            let names: Vec<String> = (0..p)
                .filter(|&j| vectors[j * p + k].abs() > 0.2)
                .map(|j| format!("`{}`", free[j].name()))
                .collect();
            return Err(FitError::Unidentifiable(names.join(", ")));
        }
    }
    Ok(())
}

/// Runs the zero-bistatic inversion when the roughness is free and the data hold at least three
/// backscatter BRDF measurements.
fn zero_bistatic_start(
    base: &MaterialSpec,
    free: &[Param],
    data: &[Measurement],
) -> Option<ZbsFit> {
    if !free.iter().any(|p| matches!(p, Param::B | Param::SigmaDeg)) {
        return None;
    }
    let points: Vec<ZbsPoint> = data
        .iter()
        .filter(|d| d.observable == Observable::Brdf)
        .filter_map(|d| {
            let v = d.geometry.angle_variables()?;
            (v.beta.abs() < 1e-6).then_some(ZbsPoint {
                theta: 0.5 * (v.theta_i + v.theta_r),
                f: d.value,
                sigma: d.sigma,
            })
        })
        .collect();
    let index = polbrdf::RefractiveIndex::new(base.n, base.k).ok()?;
    zbs::invert(&points, index, base.rho_d, base.rho_v).ok()
}
