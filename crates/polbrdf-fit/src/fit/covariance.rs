//! The uncertainties at the solution: the central-difference Jacobian in the natural
//! parameters, the covariance `(JᵀJ)⁻¹` (scaled by χ²/dof when the σ came from the residuals),
//! standard errors, correlations, the identifiability check, and the correlations of a
//! parameter at its bound at its upper limit (docs/model.md §7a, "Covariance" and "Refusals").

use super::problem::Problem;
use super::profile::UpperLimit;
use super::Bound;
use crate::error::FitError;
use crate::lm::{self, cholesky_solve};
use crate::params::Param;

/// The uncertainties of a fit's parameters (each in the order of the free parameters).
pub(super) struct Uncertainties {
    /// The covariance, NaN in the rows and columns of parameters at their bound.
    pub(super) covariance: Vec<Vec<f64>>,
    /// `sqrt(diag(covariance))`, NaN for parameters at their bound.
    pub(super) stderr: Vec<f64>,
    /// The correlation matrix.
    pub(super) correlation: Vec<Vec<f64>>,
    /// Inside the domain, or at the bound with the upper limit and correlations there.
    pub(super) bounds: Vec<Bound>,
}

/// The uncertainties at the solution `x`, whose parameters at their bound have the upper
/// `limits`, with the covariance multiplied by `scale` (χ²/dof when some σ was not given).
///
/// # Errors
/// [`FitError::Unidentifiable`] when the data cannot determine the parameters inside their
/// domain.
pub(super) fn uncertainties(
    problem: &Problem<'_>,
    x: &[f64],
    limits: &[(usize, UpperLimit)],
    scale: f64,
) -> Result<Uncertainties, FitError> {
    let free = problem.free;
    let p = free.len();
    let m = problem.rows.len();
    // Covariance in the natural parameters, of those inside their domain.
    let interior: Vec<usize> = (0..p).filter(|&j| x[j] > free[j].lower_bound()).collect();
    let jac = natural_jacobian(problem, x, m);
    let inner: Vec<Param> = interior.iter().map(|&j| free[j]).collect();
    let inner_x: Vec<f64> = interior.iter().map(|&j| x[j]).collect();
    let inner_cov = covariance_of(problem, &inner, &inner_x, &interior, &jac, scale)?;
    let mut covariance = vec![vec![f64::NAN; p]; p];
    for (a, &i) in interior.iter().enumerate() {
        for (b, &j) in interior.iter().enumerate() {
            covariance[i][j] = inner_cov[a][b];
        }
    }
    let stderr: Vec<f64> = (0..p).map(|i| covariance[i][i].max(0.0).sqrt()).collect();
    let correlation = correlation_of(&covariance);
    let bounds = bounds_of(problem, limits, scale);
    let stderr = stderr
        .into_iter()
        .enumerate()
        .map(|(j, s)| if interior.contains(&j) { s } else { f64::NAN })
        .collect();
    Ok(Uncertainties {
        covariance,
        stderr,
        correlation,
        bounds,
    })
}

/// Where each parameter ended: [`Bound::Interior`], or at its bound with its upper limit from
/// `limits` and its correlations there (the covariance at the limit with every parameter free,
/// multiplied by `scale`).
fn bounds_of(problem: &Problem<'_>, limits: &[(usize, UpperLimit)], scale: f64) -> Vec<Bound> {
    let free = problem.free;
    let p = free.len();
    let m = problem.rows.len();
    (0..p)
        .map(|j| match limits.iter().find(|l| l.0 == j) {
            None => Bound::Interior,
            Some((_, limit)) => Bound::AtLowerBound {
                upper_limit_95: limit.as_ref().map(|l| l.0),
                correlation_at_limit: limit.as_ref().and_then(|(_, xu)| {
                    let jac = natural_jacobian(problem, xu, m);
                    let all: Vec<usize> = (0..p).collect();
                    let c = covariance_of(problem, free, xu, &all, &jac, scale).ok()?;
                    Some(correlation_of(&c)[j].clone())
                }),
            },
        })
        .collect()
}

/// The covariance `(JᵀJ)⁻¹·scale` of the parameters `params` (columns `cols` of `jac`),
/// after the identifiability check.
fn covariance_of(
    problem: &Problem<'_>,
    params: &[Param],
    x: &[f64],
    cols: &[usize],
    jac: &[Vec<f64>],
    scale: f64,
) -> Result<Vec<Vec<f64>>, FitError> {
    let q = cols.len();
    let sub: Vec<Vec<f64>> = cols.iter().map(|&j| jac[j].clone()).collect();
    let (a, _) = lm::normal_equations(&sub, &vec![0.0; problem.rows.len()]);
    check_identifiable(params, &a, x, problem)?;
    // Columns of (JᵀJ)⁻¹; the matrix is symmetric, so they are also its rows.
    (0..q)
        .map(|j| {
            let e: Vec<f64> = (0..q).map(|i| f64::from(u8::from(i == j))).collect();
            cholesky_solve(&a, &e)
                .map(|col| col.into_iter().map(|v| v * scale).collect())
                .ok_or_else(|| unidentifiable_all(params))
        })
        .collect()
}

/// `C_ij/sqrt(C_ii C_jj)` (NaN where C is).
fn correlation_of(c: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let d: Vec<f64> = (0..c.len()).map(|i| c[i][i].max(0.0).sqrt()).collect();
    (0..c.len())
        .map(|i| {
            (0..c.len())
                .map(|j| c[i][j] / (d[i] * d[j]).max(f64::MIN_POSITIVE))
                .collect()
        })
        .collect()
}

/// Jacobian of the weighted residuals with respect to the natural parameters: central
/// differences with steps `1e-6·max(|x|, step scale)` (forward where a non-negative parameter
/// sits at 0).
pub(super) fn natural_jacobian(problem: &Problem<'_>, x: &[f64], m: usize) -> Vec<Vec<f64>> {
    let mut plus = vec![0.0; m];
    let mut minus = vec![0.0; m];
    let mut xp = x.to_vec();
    (0..x.len())
        .map(|j| {
            let h = problem.free[j].derivative_step(x[j]);
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
    // Sensitivity of the residual vector to a change of each parameter by its own size (by its
    // typical scale where it is smaller, e.g. 0 at its bound), against the size of the weighted
    // data.
    let data_norm = problem
        .rows
        .iter()
        .map(|&(_, _, v, w)| (v * w) * (v * w))
        .sum::<f64>()
        .sqrt()
        .max(f64::MIN_POSITIVE);
    let dead: Vec<String> = (0..p)
        .filter(|&j| {
            let change = x[j].abs().max(free[j].typical_scale());
            a[j * p + j].sqrt() * change < 1e-9 * data_norm
        })
        .map(|j| format!("`{}`", free[j].name()))
        .collect();
    if !dead.is_empty() {
        return Err(FitError::Unidentifiable(dead.join(", ")));
    }
    // Equilibrated normal matrix: a correlation matrix of the linearized problem.
    let d: Vec<f64> = (0..p).map(|j| a[j * p + j].sqrt()).collect();
    let s: Vec<f64> = (0..p * p).map(|k| a[k] / (d[k / p] * d[k % p])).collect();
    let (values, vectors) = polbrdf::numeric::linalg::symmetric_eigen_dyn(&s, p);
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
