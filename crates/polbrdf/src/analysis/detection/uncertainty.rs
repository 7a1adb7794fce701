//! The uncertainty of a detection range from the uncertainty of the fitted parameters behind
//! it (docs/detection-frame.md): linear propagation `σ_R² = J·Σ_p·Jᵀ` with the Jacobian `J` of
//! `R_max` with respect to the parameters by central finite differences.
//!
//! The step of parameter `i` is a tenth of its standard deviation `√Σ_ii`: the linearization
//! is meant over the spread the covariance gives the parameter, and the range search resolves
//! `R_max` to 1e-10 relative, far below what such a step changes. A parameter with zero variance
//! contributes nothing and is not perturbed.

use crate::error::{Error, Result};

/// Steps are this fraction of each parameter's standard deviation.
pub const STEP_FRACTION: f64 = 0.1;

/// A value with its propagated standard deviation.
#[derive(Debug, Clone, PartialEq)]
pub struct Propagated {
    /// The value at the parameters.
    pub value: f64,
    /// Its standard deviation, `√(J·Σ·Jᵀ)`.
    pub sigma: f64,
    /// `∂value/∂p_i`.
    pub jacobian: Vec<f64>,
}

impl Propagated {
    /// The interval `value ± z·sigma` (e.g. `z = 1.96` for 95 % under normality).
    pub fn interval(&self, z: f64) -> (f64, f64) {
        (self.value - z * self.sigma, self.value + z * self.sigma)
    }
}

/// Propagates the covariance `covariance` (row-major, `n × n`, symmetric) of `params` through
/// `f`: `f(params)` and `σ = √(J·Σ·Jᵀ)`. `f` returns `None` where it has no value (e.g. a range
/// "beyond" the searched limit or "not detectable"); the propagation then has none either.
///
/// # Errors
/// [`Error::InconsistentParameters`] when the covariance is not `n × n`, not finite or has a
/// negative diagonal; what `f` returns.
pub fn propagate(
    mut f: impl FnMut(&[f64]) -> Result<Option<f64>>,
    params: &[f64],
    covariance: &[f64],
) -> Result<Option<Propagated>> {
    let n = params.len();
    if covariance.len() != n * n
        || covariance.iter().any(|v| !v.is_finite())
        || (0..n).any(|i| covariance[i * n + i] < 0.0)
    {
        return Err(Error::InconsistentParameters(format!(
            "a covariance of {n} parameters needs {n}×{n} finite values with a non-negative \
             diagonal, got {} values",
            covariance.len()
        )));
    }
    let Some(value) = f(params)? else {
        return Ok(None);
    };
    let mut jacobian = vec![0.0; n];
    let mut p = params.to_vec();
    for i in 0..n {
        let h = STEP_FRACTION * covariance[i * n + i].sqrt();
        if h == 0.0 {
            continue;
        }
        p[i] = params[i] + h;
        let up = f(&p)?;
        p[i] = params[i] - h;
        let down = f(&p)?;
        p[i] = params[i];
        let (Some(up), Some(down)) = (up, down) else {
            return Ok(None);
        };
        jacobian[i] = (up - down) / (2.0 * h);
    }
    let var: f64 = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| jacobian[i] * covariance[i * n + j] * jacobian[j])
                .sum::<f64>()
        })
        .sum();
    Ok(Some(Propagated {
        value,
        sigma: var.max(0.0).sqrt(),
        jacobian,
    }))
}
