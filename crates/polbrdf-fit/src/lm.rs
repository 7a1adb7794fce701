//! A Levenberg–Marquardt least-squares minimizer (Marquardt's diagonal scaling, Nielsen's
//! damping update) with forward-difference Jacobians and lower bounds (projected steps with an
//! active set).

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

/// A least-squares objective: residuals, and their Jacobian (forward differences unless the
/// objective knows better).
pub trait Objective {
    /// Fills the `m` residuals at `u`; false where the model cannot be evaluated.
    fn residuals(&self, u: &[f64], r: &mut [f64]) -> bool;

    /// The Jacobian (column-major) at `u`, where `r` holds the residuals at `u` — the point the
    /// minimizer evaluated last. `None` if the model fails at a perturbed point.
    fn jacobian(&self, u: &[f64], r: &[f64]) -> Option<Vec<Vec<f64>>> {
        jacobian(&|u: &[f64], out: &mut [f64]| self.residuals(u, out), u, r)
    }
}

impl<F: Fn(&[f64], &mut [f64]) -> bool> Objective for F {
    fn residuals(&self, u: &[f64], r: &mut [f64]) -> bool {
        self(u, r)
    }
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

/// Minimizes `Σ r(u)²` from `u0` subject to `u ≥ lower` (componentwise; `−∞` for none).
/// `f(u, r)` fills the `m` residuals and returns false where the model cannot be evaluated
/// (such a step is rejected).
///
/// Bounds: a coordinate at its bound whose gradient points out of the domain is held there
/// (the active set, recomputed every iteration); the step of the others is solved for and then
/// projected onto the domain. Forward differences step inward from a bound, so the model is
/// never evaluated outside it. Converged as without bounds, with the gradient test on the free
/// coordinates only.
pub fn minimize(
    f: &impl Objective,
    u0: &[f64],
    lower: &[f64],
    m: usize,
    opts: &LmOptions,
) -> LmReport {
    let p = u0.len();
    assert_eq!(lower.len(), p, "one bound per coordinate");
    let mut u: Vec<f64> = u0.iter().zip(lower).map(|(x, l)| x.max(*l)).collect();
    let mut r = vec![0.0; m];
    let report = |u: Vec<f64>, chi2, iterations, converged, message: &str| LmReport {
        u,
        chi2,
        iterations,
        converged,
        message: message.to_string(),
    };
    if !f.residuals(&u, &mut r) {
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
        let Some(jac) = f.jacobian(&u, &r) else {
            return report(
                u,
                chi2,
                iterations,
                false,
                "the model cannot be evaluated near the current point",
            );
        };
        let (a, g) = normal_equations(&jac, &r);
        // Held at the bound: the descent direction −g points out of the domain.
        let active: Vec<bool> = (0..p).map(|i| u[i] <= lower[i] && g[i] >= 0.0).collect();
        let diag: Vec<f64> = (0..p).map(|i| a[i * p + i].max(1e-300)).collect();
        let grad = (0..p)
            .filter(|&i| !active[i])
            .map(|i| g[i].abs() / (chi2 * diag[i]).sqrt())
            .fold(0.0, f64::max);
        if grad < opts.gtol {
            return report(u, chi2, iterations, true, "gradient vanishes");
        }
        if lambda < 0.0 {
            lambda = 1e-3;
        }
        // The damped step on the coordinates not held; a coordinate at its bound that the step
        // would push out is held too, and the step solved again.
        let solve = |lambda: f64| -> Option<Vec<f64>> {
            let mut held = active.clone();
            loop {
                let free: Vec<usize> = (0..p).filter(|&i| !held[i]).collect();
                let q = free.len();
                let mut damped = vec![0.0; q * q];
                for (x, &i) in free.iter().enumerate() {
                    for (y, &j) in free.iter().enumerate() {
                        damped[x * q + y] = a[i * p + j];
                    }
                    damped[x * q + x] += lambda * diag[i];
                }
                let neg_g: Vec<f64> = free.iter().map(|&i| -g[i]).collect();
                let step = cholesky_solve(&damped, &neg_g)?;
                let blocked: Vec<usize> = free
                    .iter()
                    .zip(&step)
                    .filter(|(&i, s)| u[i] <= lower[i] && **s < 0.0)
                    .map(|(&i, _)| i)
                    .collect();
                if blocked.is_empty() {
                    let mut d = vec![0.0; p];
                    for (x, &i) in free.iter().enumerate() {
                        d[i] = step[x];
                    }
                    return Some(d);
                }
                for i in blocked {
                    held[i] = true;
                }
            }
        };
        loop {
            iterations += 1;
            let Some(step) = solve(lambda) else {
                lambda *= nu;
                nu *= 2.0;
                if iterations >= opts.max_iterations {
                    break 'outer;
                }
                continue;
            };
            // Along the step as far as the domain allows: the first bound it meets stops it
            // there (so the step stays a descent direction, which a projection would not).
            let (alpha, stop) = (0..p)
                .filter(|&i| step[i] < 0.0 && lower[i].is_finite())
                .map(|i| ((lower[i] - u[i]) / step[i], i))
                .filter(|(t, _)| *t < 1.0)
                .fold(
                    (1.0, None),
                    |acc, (t, i)| if t < acc.0 { (t, Some(i)) } else { acc },
                );
            let mut u_new: Vec<f64> = (0..p).map(|i| u[i] + alpha * step[i]).collect();
            if let Some(i) = stop {
                u_new[i] = lower[i];
            }
            for i in 0..p {
                u_new[i] = u_new[i].max(lower[i]);
            }
            let delta: Vec<f64> = u_new.iter().zip(&u).map(|(a, b)| a - b).collect();
            let ok = f.residuals(&u_new, &mut r_new);
            let chi2_new: f64 = if ok {
                r_new.iter().map(|x| x * x).sum()
            } else {
                f64::INFINITY
            };
            // Predicted reduction of the linear model, −(2gᵀδ + δᵀJᵀJδ) (for the full damped
            // step this is δᵀ(λ·D·δ − g)).
            let quad: f64 = (0..p)
                .map(|i| delta[i] * (0..p).map(|j| a[i * p + j] * delta[j]).sum::<f64>())
                .sum();
            let predicted = -(2.0 * (0..p).map(|i| g[i] * delta[i]).sum::<f64>() + quad);
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
