//! A Levenberg–Marquardt least-squares minimizer (Marquardt's diagonal scaling, Nielsen's
//! damping update) with forward-difference Jacobians.

/// Stopping rules.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LmOptions {
    /// Give up after this many accepted or rejected steps.
    pub max_iterations: usize,
    /// Converged when an accepted step lowers χ² by less than `ftol·χ²`…
    pub ftol: f64,
    /// …and changes every coordinate by less than `xtol·(|u| + xtol)`.
    pub xtol: f64,
    /// Or when the scaled gradient `max|Jᵀr|/sqrt(χ²·diag(JᵀJ))` is below `gtol`.
    pub gtol: f64,
}

impl Default for LmOptions {
    fn default() -> Self {
        Self {
            max_iterations: 200,
            ftol: 1e-12,
            xtol: 1e-9,
            gtol: 1e-10,
        }
    }
}

/// Outcome of a minimization.
#[derive(Debug, Clone, PartialEq)]
pub struct LmReport {
    /// The best point found.
    pub u: Vec<f64>,
    /// χ² = Σ r² there.
    pub chi2: f64,
    /// Steps taken (accepted and rejected).
    pub iterations: usize,
    /// Whether a convergence test was met.
    pub converged: bool,
    /// Which test stopped it, in words.
    pub message: String,
}

/// Forward-difference Jacobian of `f` at `u`, where `r` = f(u) (column-major: `jac[j]` is
/// ∂r/∂u_j), with steps `h_j = sqrt(ε)·max(|u_j|, 1)`: p evaluations instead of 2p, and accurate
/// to ~1e-8 relative — ample for the step direction (the covariance uses its own
/// central-difference Jacobian). Returns `None` if `f` fails at a perturbed point.
pub fn jacobian(
    f: &(impl Fn(&[f64], &mut [f64]) -> bool + ?Sized),
    u: &[f64],
    r: &[f64],
) -> Option<Vec<Vec<f64>>> {
    let mut cols = Vec::with_capacity(u.len());
    let mut plus = vec![0.0; r.len()];
    let mut up = u.to_vec();
    for j in 0..u.len() {
        let h = f64::EPSILON.sqrt() * u[j].abs().max(1.0);
        up[j] = u[j] + h;
        let ok = f(&up, &mut plus);
        let step = up[j] - u[j]; // the step actually representable
        up[j] = u[j];
        if !ok {
            return None;
        }
        cols.push(plus.iter().zip(r).map(|(p, q)| (p - q) / step).collect());
    }
    Some(cols)
}

/// `JᵀJ` (p×p, row-major) and `Jᵀr` of a column-major Jacobian.
pub fn normal_equations(jac: &[Vec<f64>], r: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let p = jac.len();
    let mut a = vec![0.0; p * p];
    for i in 0..p {
        for j in 0..=i {
            let v: f64 = jac[i].iter().zip(&jac[j]).map(|(x, y)| x * y).sum();
            a[i * p + j] = v;
            a[j * p + i] = v;
        }
    }
    let g = jac
        .iter()
        .map(|c| c.iter().zip(r).map(|(x, y)| x * y).sum())
        .collect();
    (a, g)
}

/// Solves the symmetric positive definite system `a·x = b` (row-major p×p) by Cholesky;
/// `None` if `a` is not positive definite.
pub fn cholesky_solve(a: &[f64], b: &[f64]) -> Option<Vec<f64>> {
    let p = b.len();
    let mut l = vec![0.0; p * p];
    for i in 0..p {
        for j in 0..=i {
            let s: f64 = a[i * p + j] - (0..j).map(|k| l[i * p + k] * l[j * p + k]).sum::<f64>();
            if i == j {
                if s.is_nan() || s <= 0.0 {
                    return None;
                }
                l[i * p + i] = s.sqrt();
            } else {
                l[i * p + j] = s / l[j * p + j];
            }
        }
    }
    let mut y = vec![0.0; p];
    for i in 0..p {
        y[i] = (b[i] - (0..i).map(|k| l[i * p + k] * y[k]).sum::<f64>()) / l[i * p + i];
    }
    let mut x = vec![0.0; p];
    for i in (0..p).rev() {
        x[i] = (y[i] - (i + 1..p).map(|k| l[k * p + i] * x[k]).sum::<f64>()) / l[i * p + i];
    }
    Some(x)
}

/// Minimizes `Σ r(u)²` from `u0`. `f(u, r)` fills the `m` residuals and returns false where the
/// model cannot be evaluated (such a step is rejected).
pub fn minimize(
    f: &(impl Fn(&[f64], &mut [f64]) -> bool + ?Sized),
    u0: &[f64],
    m: usize,
    opts: &LmOptions,
) -> LmReport {
    let p = u0.len();
    let mut u = u0.to_vec();
    let mut r = vec![0.0; m];
    let report = |u: Vec<f64>, chi2, iterations, converged, message: &str| LmReport {
        u,
        chi2,
        iterations,
        converged,
        message: message.to_string(),
    };
    if !f(&u, &mut r) {
        return report(
            u,
            f64::INFINITY,
            0,
            false,
            "the model cannot be evaluated at the start values",
        );
    }
    let mut chi2: f64 = r.iter().map(|x| x * x).sum();
    let mut lambda = -1.0;
    let mut nu = 2.0;
    let mut r_new = vec![0.0; m];
    let mut iterations = 0;
    'outer: while iterations < opts.max_iterations {
        if chi2 == 0.0 {
            return report(u, chi2, iterations, true, "exact fit (χ² = 0)");
        }
        let Some(jac) = jacobian(f, &u, &r) else {
            return report(
                u,
                chi2,
                iterations,
                false,
                "the model cannot be evaluated near the current point",
            );
        };
        let (a, g) = normal_equations(&jac, &r);
        let diag: Vec<f64> = (0..p).map(|i| a[i * p + i].max(1e-300)).collect();
        let grad = (0..p)
            .map(|i| g[i].abs() / (chi2 * diag[i]).sqrt())
            .fold(0.0, f64::max);
        if grad < opts.gtol {
            return report(u, chi2, iterations, true, "gradient vanishes");
        }
        if lambda < 0.0 {
            lambda = 1e-3;
        }
        loop {
            iterations += 1;
            let mut damped = a.clone();
            for i in 0..p {
                damped[i * p + i] += lambda * diag[i];
            }
            let neg_g: Vec<f64> = g.iter().map(|x| -x).collect();
            let Some(delta) = cholesky_solve(&damped, &neg_g) else {
                lambda *= nu;
                nu *= 2.0;
                if iterations >= opts.max_iterations {
                    break 'outer;
                }
                continue;
            };
            let u_new: Vec<f64> = u.iter().zip(&delta).map(|(x, d)| x + d).collect();
            let ok = f(&u_new, &mut r_new);
            let chi2_new: f64 = if ok {
                r_new.iter().map(|x| x * x).sum()
            } else {
                f64::INFINITY
            };
            // Predicted reduction of the linear model: δᵀ(λ·D·δ − g).
            let predicted: f64 = (0..p)
                .map(|i| delta[i] * (lambda * diag[i] * delta[i] - g[i]))
                .sum();
            if chi2_new.is_finite() && chi2_new < chi2 {
                let rho = (chi2 - chi2_new) / predicted.max(f64::MIN_POSITIVE);
                lambda *= (1.0 / 3.0f64).max(1.0 - (2.0 * rho - 1.0).powi(3));
                nu = 2.0;
                let small_f = chi2 - chi2_new <= opts.ftol * chi2_new;
                let small_x = delta
                    .iter()
                    .zip(&u_new)
                    .all(|(d, x)| d.abs() <= opts.xtol * (x.abs() + opts.xtol));
                u = u_new;
                std::mem::swap(&mut r, &mut r_new);
                chi2 = chi2_new;
                if small_f && small_x {
                    return report(u, chi2, iterations, true, "χ² and parameters stationary");
                }
                continue 'outer;
            }
            lambda *= nu;
            nu *= 2.0;
            if lambda > 1e16 {
                // No step of any length lowers χ²: a minimum to machine precision.
                return report(
                    u,
                    chi2,
                    iterations,
                    true,
                    "no further decrease possible (minimum to rounding)",
                );
            }
            if iterations >= opts.max_iterations {
                break 'outer;
            }
        }
    }
    report(
        u,
        chi2,
        iterations,
        false,
        &format!("not converged after {} iterations", opts.max_iterations),
    )
}
