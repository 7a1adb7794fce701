//! A parameter at the lower bound of its domain: its one-sided 95 % upper limit from the profile
//! of χ², or a better point inside the domain from which the fit resumes (docs/model.md §7a, "A
//! parameter at its bound").

use super::objective::FitObjective;
use super::problem::Problem;
use crate::lm::{self, cholesky_solve, LmOptions};

/// `Δχ²` of a one-sided 95 % limit: `1.6449²`.
const ONE_SIDED_95: f64 = 2.705_543_454_095_404;

/// A one-sided upper limit and the best parameters there (`None`: the data do not bound it).
pub(super) type UpperLimit = Option<(f64, Vec<f64>)>;

/// What the profile of a parameter at its bound found.
enum Profile {
    /// The one-sided upper limit and the best parameters there.
    Limit(UpperLimit),
    /// A point inside the domain with a lower χ² than the fit's.
    Better(Vec<f64>),
}

/// The profiles of the parameters of `x` at their lower bound (χ² `chi2`, one-sided 95 % rise
/// `ONE_SIDED_95·unit`), in order: their upper limits, and — when a profile finds a point
/// below `chi2` — that point, which ends the search (the limits found before it are kept).
pub(super) fn upper_limits(
    problem: &Problem<'_>,
    x: &[f64],
    chi2: f64,
    unit: f64,
    lm: &LmOptions,
) -> (Vec<(usize, UpperLimit)>, Option<Vec<f64>>) {
    let mut limits = Vec::new();
    for j in (0..x.len()).filter(|&j| x[j] <= problem.free[j].lower_bound()) {
        match profile_upper_limit(problem, x, j, chi2, ONE_SIDED_95 * unit, lm) {
            Profile::Limit(l) => limits.push((j, l)),
            Profile::Better(x2) => return (limits, Some(x2)),
        }
    }
    (limits, None)
}

/// A first guess of where the profile χ² of parameter `j` (at its bound in `x`) rises by
/// `delta`, from the quadratic model of χ² in the internal coordinates at `x`: with the
/// gradient `g` and the Schur complement `S` of `JᵀJ` for coordinate `j` (the others
/// re-optimized), `Δχ²(u) ≈ 2g·u + S·u²` from the bound; `None` where the model says nothing.
fn profile_guess(problem: &Problem<'_>, x: &[f64], j: usize, delta: f64) -> Option<f64> {
    use lm::Objective;
    let p = x.len();
    let objective = FitObjective::new(problem, x, (0..p).collect());
    let u: Vec<f64> = (0..p).map(|i| problem.free[i].to_internal(x[i])).collect();
    let mut r = vec![0.0; problem.rows.len()];
    if !objective.residuals(&u, &mut r) {
        return None;
    }
    let jac = objective.jacobian(&u, &r)?;
    let (a, g) = lm::normal_equations(&jac, &r);
    // S = A_jj − A_jo·A_oo⁻¹·A_oj.
    let others: Vec<usize> = (0..p).filter(|&i| i != j).collect();
    let q = others.len();
    let mut s = a[j * p + j];
    if q > 0 {
        let a_oo: Vec<f64> = others
            .iter()
            .flat_map(|&i| others.iter().map(move |&k| (i, k)))
            .map(|(i, k)| a[i * p + k])
            .collect();
        let a_oj: Vec<f64> = others.iter().map(|&i| a[i * p + j]).collect();
        let y = cholesky_solve(&a_oo, &a_oj)?;
        s -= a_oj.iter().zip(&y).map(|(a, b)| a * b).sum::<f64>();
    }
    let gj = g[j].max(0.0);
    if s.is_nan() || s <= 0.0 {
        return None;
    }
    let du = (-gj + (gj * gj + s * delta).sqrt()) / s;
    Some(problem.free[j].from_internal(u[j] + du))
}

/// The profile χ² of parameter `j` at value `t` — the best χ² over the other free parameters
/// with parameter `j` held at `t`, started from `x` — and the parameters there.
fn profile_at(
    problem: &Problem<'_>,
    x: &[f64],
    j: usize,
    t: f64,
    lm: &LmOptions,
) -> (f64, Vec<f64>) {
    let mut x0 = x.to_vec();
    x0[j] = t;
    if problem.free.len() == 1 {
        return (problem.chi2(&x0), x0);
    }
    let (xt, report) = problem.minimize(&x0, &[j], lm);
    (report.chi2, xt)
}

/// The value of parameter `j` (at its lower bound in `x`, with χ² `chi2`) where its profile χ²
/// has risen by `delta` — the one-sided 95 % upper limit — to 0.5 % of `delta`: a secant search
/// in `(ln t, ln Δχ²)` (exact for `Δχ² ∝ tᵖ`), bracketed, each profile fit started from the
/// previous one's parameters. Unbounded when χ² has not risen that much by 10⁶ times the
/// parameter's typical scale; [`Profile::Better`] if some point of the profile lies below `chi2`
/// (by more than its rounding).
fn profile_upper_limit(
    problem: &Problem<'_>,
    x: &[f64],
    j: usize,
    chi2: f64,
    delta: f64,
    lm: &LmOptions,
) -> Profile {
    let lm = LmOptions {
        ftol: 1e-10,
        xtol: 1e-7,
        ..*lm
    };
    let bound = x[j];
    let scale = problem.free[j].typical_scale();
    let rounding = 1e-9 * chi2.abs().max(1.0);
    let mut t = profile_guess(problem, x, j, delta)
        .filter(|t| *t > bound && t.is_finite())
        .unwrap_or(bound + scale);
    let mut warm = x.to_vec();
    // (distance from the bound, Δχ², parameters) on either side of the target.
    let mut below: Option<(f64, f64)> = None;
    let mut above: Option<(f64, f64, Vec<f64>)> = None;
    for _ in 0..40 {
        let (c, xt) = profile_at(problem, &warm, j, t, &lm);
        let d = c - chi2;
        if d < -rounding {
            return Profile::Better(xt);
        }
        let dist = t - bound;
        if (d - delta).abs() <= 5e-3 * delta {
            return Profile::Limit(Some((t, xt)));
        }
        if d < delta {
            below = Some((dist, d.max(rounding)));
        } else {
            above = Some((dist, d, xt.clone()));
        }
        warm = xt;
        let next = match (&below, &above) {
            (Some((t0, d0)), Some((t1, d1, _))) => {
                // Secant in (ln t, ln Δ), kept inside the bracket.
                let p = (d1 / d0).ln() / (t1 / t0).ln();
                let guess = t0 * (delta / d0).powf(1.0 / p.max(0.5));
                guess.clamp(t0 + 0.05 * (t1 - t0), t1 - 0.05 * (t1 - t0))
            }
            // One side only: as if Δ ∝ t³ (between the t² of a linear rise in k² and the t⁴
            // of a quadratic one), by at most ×10.
            (Some((t0, d0)), None) => t0 * (delta / d0).cbrt().clamp(1.0, 10.0),
            (None, Some((t1, d1, _))) => t1 * (delta / d1).cbrt().clamp(0.1, 1.0),
            (None, None) => unreachable!("one side is set"),
        };
        if next > 1e6 * scale {
            return Profile::Limit(None);
        }
        t = bound + next;
    }
    Profile::Limit(above.map(|(d, _, xt)| (bound + d, xt)))
}
