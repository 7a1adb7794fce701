//! From the best start to the solution: the last digits by Gauss–Newton steps, parameters the
//! data cannot tell from their bound put there, the profiles of those at a bound, and the fit
//! resumed from a better point a profile finds (docs/model.md §7a, "The last digits" and "A
//! parameter at its bound").

use super::covariance::natural_jacobian;
use super::problem::Problem;
use super::profile::{upper_limits, UpperLimit};
use crate::lm::{self, cholesky_solve, LmOptions, LmReport};

/// Where a fit ended.
pub(super) struct Solution {
    /// The parameters' natural values.
    pub(super) x: Vec<f64>,
    /// The minimizer's report of the run that found them, with χ² at `x`.
    pub(super) best: LmReport,
    /// The one-sided upper limits of the parameters at their lower bound.
    pub(super) limits: Vec<(usize, UpperLimit)>,
}

/// The solution from the best start's `x` and report `best`: polished (unless the minimizer
/// stopped on a vanishing gradient), parameters indistinguishable from their bound put there,
/// and the upper limits of those at a bound — or, when a profile finds a lower χ² inside the
/// domain, the fit resumed from there (at most 3 times) and all of this again. `scaled`: the
/// χ² unit is χ²/dof (some σ not given), else 1.
pub(super) fn settle(
    problem: &Problem<'_>,
    x: Vec<f64>,
    best: LmReport,
    scaled: bool,
    lm: &LmOptions,
) -> Solution {
    let (m, p) = (problem.rows.len(), problem.free.len());
    let (mut x, mut best) = (x, best);
    let mut limits: Vec<(usize, UpperLimit)>;
    let mut resumed = 0;
    loop {
        // The last digits: Gauss–Newton steps on the central-difference Jacobian (not needed
        // where the minimizer stopped on a vanishing gradient, within 1e-7 standard errors).
        if !best.message.starts_with("gradient") {
            x = polish(problem, x, best.chi2);
        }
        best.chi2 = problem.chi2(&x);
        let unit = if scaled {
            best.chi2 / (m - p) as f64
        } else {
            1.0
        };
        snap_to_bounds(problem, &mut x, &mut best.chi2, unit);
        let better;
        (limits, better) = upper_limits(problem, &x, best.chi2, unit, lm);
        match better {
            Some(x2) if resumed < 3 => {
                resumed += 1;
                let (x3, report) = problem.minimize(&x2, &[], lm);
                if report.chi2 < best.chi2 {
                    (x, best) = (x3, report);
                }
            }
            _ => break,
        }
    }
    Solution { x, best, limits }
}

/// Puts at its bound each non-negative parameter the data cannot tell from it: χ² with it at
/// the bound within 1e-6·`unit` — a thousandth of a standard error — of the best `chi2`, or of
/// χ²'s rounding (lowering `chi2` where that is lower). It approaches 0 only asymptotically
/// where χ² is flat there (e.g. data the model fits exactly).
fn snap_to_bounds(problem: &Problem<'_>, x: &mut Vec<f64>, chi2: &mut f64, unit: f64) {
    for j in 0..x.len() {
        let bound = problem.free[j].lower_bound();
        if bound.is_finite() && x[j] > bound {
            let mut at = x.clone();
            at[j] = bound;
            let c = problem.chi2(&at);
            if c <= *chi2 + (1e-6 * unit).max(1e-9 * *chi2) {
                *x = at;
                *chi2 = chi2.min(c);
            }
        }
    }
}

/// Gauss–Newton steps from the minimizer's result `x` on the central-difference Jacobian in the
/// natural parameters, until the step is below 1e-8 standard errors (at most 8 steps), for the
/// parameters inside their domain.
///
/// Levenberg–Marquardt judges a step by the decrease of χ², which near the minimum is below
/// χ²'s own rounding (~1e-11 for 10⁴ values, a step of ~3e-6 standard errors), and its
/// forward-difference Jacobian is accurate to ~1e-8; so its result can sit 1e-5 standard
/// errors from the minimum. There the quadratic model is exact to second order, and the
/// central-difference gradient (accurate to ~1e-10) locates the minimum itself. Only a point
/// already within 1e-2 standard errors is polished; a step that fails to evaluate or leaves the
/// domain ends it.
fn polish(problem: &Problem<'_>, mut x: Vec<f64>, chi2: f64) -> Vec<f64> {
    let m = problem.rows.len();
    let p = x.len();
    let unit = (chi2 / m.saturating_sub(p).max(1) as f64).max(1.0);
    let mut r = vec![0.0; m];
    let mut last = f64::INFINITY;
    for _ in 0..8 {
        if !problem.residuals(&x, &mut r) {
            break;
        }
        let free: Vec<usize> = (0..p)
            .filter(|&j| x[j] > problem.free[j].lower_bound())
            .collect();
        if free.is_empty() {
            break;
        }
        let jac = natural_jacobian(problem, &x, m);
        let cols: Vec<Vec<f64>> = free.iter().map(|&j| jac[j].clone()).collect();
        let (a, g) = lm::normal_equations(&cols, &r);
        let Some(step) = cholesky_solve(&a, &g) else {
            break;
        };
        let decrement: f64 = step.iter().zip(&g).map(|(s, g)| s * g).sum();
        let near = decrement <= 1e-4 * unit; // false for NaN
                                             // Done at 1e-8 standard errors, or when a step no longer shortens the next (the noise
                                             // floor of the derivatives).
        if !near || decrement <= 1e-16 * unit || decrement > 0.25 * last {
            break;
        }
        last = decrement;
        let mut next = x.clone();
        for (k, &j) in free.iter().enumerate() {
            next[j] = x[j] - step[k];
        }
        let inside = free.iter().all(|&j| {
            let param = problem.free[j];
            if param.strictly_positive() {
                next[j] > 0.0
            } else {
                next[j] >= 0.0
            }
        });
        if !inside || !problem.residuals(&next, &mut r) {
            break;
        }
        x = next;
    }
    x
}
