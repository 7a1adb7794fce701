//! A Levenberg–Marquardt least-squares minimizer (Marquardt's diagonal scaling, Nielsen's
//! damping update, as in Madsen, Nielsen & Tingleff 2004, §3.2) with forward-difference
//! Jacobians and lower bounds (projected steps with an active set).

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
/// The iteration is Levenberg–Marquardt as in Madsen, Nielsen & Tingleff, *Methods for
/// Non-Linear Least Squares Problems* (2nd ed., IMM, DTU, 2004), §3.2: at each point the
/// Jacobian and the normal equations, then damped trial steps `(JᵀJ + λ·D)·δ = −Jᵀr` with
/// Marquardt's scaling `D = diag(JᵀJ)` (Marquardt, SIAM J. Appl. Math. 11, 431, 1963) until
/// one lowers χ², λ following Nielsen's update by the gain ratio (`λ·max(1/3, 1 − (2ρ − 1)³)`
/// after an accepted step, `λ·ν` with ν doubling after a rejected one); each trial step counts
/// as an iteration.
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
    assert_eq!(lower.len(), u0.len(), "one bound per coordinate");
    let u: Vec<f64> = u0.iter().zip(lower).map(|(x, l)| x.max(*l)).collect();
    let mut r = vec![0.0; m];
    if !f.residuals(&u, &mut r) {
        return LmReport {
            u,
            chi2: f64::INFINITY,
            iterations: 0,
            converged: false,
            message: "the model cannot be evaluated at the start values".into(),
        };
    }
    let mut state = State {
        chi2: r.iter().map(|x| x * x).sum(),
        u,
        r,
        r_new: vec![0.0; m],
        damping: Damping::new(),
        iterations: 0,
    };
    while state.iterations < opts.max_iterations {
        if let Some(stop) = state.iterate(f, lower, opts) {
            return state.report(stop.converged, stop.message);
        }
    }
    let message = format!("not converged after {} iterations", opts.max_iterations);
    state.report(false, &message)
}

/// Why a minimization stopped before its iteration limit.
struct Stop {
    /// Whether a convergence test was met.
    converged: bool,
    /// Which, in words.
    message: &'static str,
}

impl Stop {
    /// A stop on the convergence test `message`.
    fn converged(message: &'static str) -> Option<Self> {
        Some(Stop {
            converged: true,
            message,
        })
    }
}

/// The minimizer between iterations: the point, its residuals and χ², the damping, and the
/// steps taken (accepted and rejected).
struct State {
    u: Vec<f64>,
    r: Vec<f64>,
    /// The residuals at the trial point (swapped with `r` when it is accepted).
    r_new: Vec<f64>,
    chi2: f64,
    damping: Damping,
    iterations: usize,
}

impl State {
    /// The outcome at the current point.
    fn report(self, converged: bool, message: &str) -> LmReport {
        LmReport {
            u: self.u,
            chi2: self.chi2,
            iterations: self.iterations,
            converged,
            message: message.to_string(),
        }
    }

    /// One iteration: the convergence tests at the current point (χ² = 0, a vanishing scaled
    /// gradient), then damped trial steps until one lowers χ² and is accepted. `Some` when the
    /// minimization stops; `None` to go on (the caller stops at the iteration limit, which a
    /// trial step may reach).
    fn iterate(&mut self, f: &impl Objective, lower: &[f64], opts: &LmOptions) -> Option<Stop> {
        if self.chi2 == 0.0 {
            return Stop::converged("exact fit (χ² = 0)");
        }
        let Some(jac) = f.jacobian(&self.u, &self.r) else {
            return Some(Stop {
                converged: false,
                message: "the model cannot be evaluated near the current point",
            });
        };
        let normal = Normal::new(&jac, &self.r, &self.u, lower);
        if normal.scaled_gradient(self.chi2) < opts.gtol {
            return Stop::converged("gradient vanishes");
        }
        loop {
            self.iterations += 1;
            if let Some(step) = normal.damped_step(self.damping.lambda, &self.u, lower) {
                let u_new = along_step(&self.u, &step, lower);
                let ok = f.residuals(&u_new, &mut self.r_new);
                let chi2_new: f64 = if ok {
                    self.r_new.iter().map(|x| x * x).sum()
                } else {
                    f64::INFINITY
                };
                if chi2_new.is_finite() && chi2_new < self.chi2 {
                    return self.accept(u_new, chi2_new, &normal, opts);
                }
                self.damping.reject();
                if self.damping.lambda > 1e16 {
                    // No step of any length lowers χ²: a minimum to machine precision.
                    return Stop::converged("no further decrease possible (minimum to rounding)");
                }
            } else {
                // The damped matrix is not positive definite: more damping.
                self.damping.reject();
            }
            if self.iterations >= opts.max_iterations {
                return None;
            }
        }
    }

    /// Accepts the trial point `u_new` (χ² `chi2_new`, its residuals in `r_new`): λ updated by
    /// the gain ratio `ρ = (χ² − χ²_new)/predicted reduction`, and the convergence test on the
    /// step — `Some` when χ² and the parameters are stationary ([`stationary`]).
    fn accept(
        &mut self,
        u_new: Vec<f64>,
        chi2_new: f64,
        normal: &Normal,
        opts: &LmOptions,
    ) -> Option<Stop> {
        let delta: Vec<f64> = u_new.iter().zip(&self.u).map(|(a, b)| a - b).collect();
        let predicted = normal.predicted_reduction(&delta);
        let rho = (self.chi2 - chi2_new) / predicted.max(f64::MIN_POSITIVE);
        self.damping.accept(rho);
        let done = stationary(self.chi2, chi2_new, &delta, &u_new, opts);
        self.u = u_new;
        std::mem::swap(&mut self.r, &mut self.r_new);
        self.chi2 = chi2_new;
        if done {
            return Stop::converged("χ² and parameters stationary");
        }
        None
    }
}

/// Nielsen's damping (H. B. Nielsen, *Damping parameter in Marquardt's method*, IMM-REP-1999-05,
/// DTU; Madsen, Nielsen & Tingleff §3.2): λ, relative to Marquardt's scaling `diag(JᵀJ)`, and
/// its growth factor ν after rejections.
struct Damping {
    lambda: f64,
    nu: f64,
}

impl Damping {
    /// λ = 10⁻³, ν = 2.
    fn new() -> Self {
        Damping {
            lambda: 1e-3,
            nu: 2.0,
        }
    }

    /// After an accepted step of gain ratio `rho`: `λ·max(1/3, 1 − (2ρ − 1)³)`, and ν = 2.
    fn accept(&mut self, rho: f64) {
        self.lambda *= (1.0 / 3.0f64).max(1.0 - (2.0 * rho - 1.0).powi(3));
        self.nu = 2.0;
    }

    /// After a rejected step: `λ·ν`, and ν doubled.
    fn reject(&mut self) {
        self.lambda *= self.nu;
        self.nu *= 2.0;
    }
}

/// The linearized problem at the current point `u`: `JᵀJ` (p×p, row-major), `Jᵀr`,
/// Marquardt's scaling `diag(JᵀJ)` (at least 1e-300) and the active set.
struct Normal {
    a: Vec<f64>,
    g: Vec<f64>,
    diag: Vec<f64>,
    /// Held at the bound: the descent direction −g points out of the domain.
    active: Vec<bool>,
}

impl Normal {
    /// From the Jacobian `jac` and residuals `r` at `u`, with the bounds `lower`.
    fn new(jac: &[Vec<f64>], r: &[f64], u: &[f64], lower: &[f64]) -> Self {
        let p = u.len();
        let (a, g) = normal_equations(jac, r);
        let active = (0..p).map(|i| u[i] <= lower[i] && g[i] >= 0.0).collect();
        let diag = (0..p).map(|i| a[i * p + i].max(1e-300)).collect();
        Normal { a, g, diag, active }
    }

    /// The scaled gradient `max|Jᵀr|/sqrt(χ²·diag(JᵀJ))` over the coordinates not held — the
    /// largest cosine between the residual vector and a column of `J` (MINPACK's `gtol` test).
    fn scaled_gradient(&self, chi2: f64) -> f64 {
        (0..self.g.len())
            .filter(|&i| !self.active[i])
            .map(|i| self.g[i].abs() / (chi2 * self.diag[i]).sqrt())
            .fold(0.0, f64::max)
    }

    /// The damped step `(JᵀJ + λ·D)·δ = −Jᵀr` on the coordinates not held (0 on the others);
    /// a coordinate at its bound that the step would push out is held too, and the step solved
    /// again. `None` if the damped matrix is not positive definite.
    fn damped_step(&self, lambda: f64, u: &[f64], lower: &[f64]) -> Option<Vec<f64>> {
        let (a, g, diag) = (&self.a, &self.g, &self.diag);
        let p = g.len();
        let mut held = self.active.clone();
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
    }

    /// The reduction of χ² the linear model predicts for the step `delta`,
    /// `−(2gᵀδ + δᵀJᵀJδ)` (for the full damped step this is `δᵀ(λ·D·δ − g)`).
    fn predicted_reduction(&self, delta: &[f64]) -> f64 {
        let (a, g) = (&self.a, &self.g);
        let p = g.len();
        let quad: f64 = (0..p)
            .map(|i| delta[i] * (0..p).map(|j| a[i * p + j] * delta[j]).sum::<f64>())
            .sum();
        -(2.0 * (0..p).map(|i| g[i] * delta[i]).sum::<f64>() + quad)
    }
}

/// The trial point from `u` along `step` as far as the domain allows: the first bound it meets
/// stops it there (so the step stays a descent direction, which a projection would not).
fn along_step(u: &[f64], step: &[f64], lower: &[f64]) -> Vec<f64> {
    let p = u.len();
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
    u_new
}

/// The convergence test of an accepted step from χ² `chi2` to `chi2_new` by `delta` (to
/// `u_new`): χ² lowered by at most `ftol·χ²_new` and every coordinate changed by at most
/// `xtol·(|u| + xtol)`.
fn stationary(chi2: f64, chi2_new: f64, delta: &[f64], u_new: &[f64], opts: &LmOptions) -> bool {
    let small_f = chi2 - chi2_new <= opts.ftol * chi2_new;
    let small_x = delta
        .iter()
        .zip(u_new)
        .all(|(d, x)| d.abs() <= opts.xtol * (x.abs() + opts.xtol));
    small_f && small_x
}
