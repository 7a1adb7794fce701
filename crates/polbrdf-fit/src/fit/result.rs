//! What a fit returns: the fitted values with their uncertainties, where each parameter ended
//! relative to its domain, and every measurement beside the model.

use crate::params::Param;
use crate::zbs::ZbsFit;
use polbrdf::MaterialSpec;

/// Where a fitted parameter ended, relative to its domain.
#[derive(Debug, Clone, PartialEq)]
pub enum Bound {
    /// Inside its domain: the value and its standard error describe it.
    Interior,
    /// At the lower bound of its domain (0 for k, a, ρ_D, ρ_V): the data prefer a value at or
    /// below it. A standard error means nothing there (at k = 0 the model is even in k, so the
    /// derivative vanishes): the result is the bound with a one-sided upper limit, and the
    /// parameter's row of the covariance is NaN (the others' covariance is conditional on it).
    AtLowerBound {
        /// The one-sided 95 % upper limit from the profile of χ²: the value at which the best χ²
        /// over the other free parameters has risen by 2.706 (× χ²/dof when the uncertainties
        /// come from the residuals); `None` if χ² never rises that much (the data do not bound
        /// the parameter).
        upper_limit_95: Option<f64>,
        /// The parameter's correlation with every free parameter (in their order), at the
        /// upper limit (the other parameters at their best values there): what the parameter
        /// trades off against, e.g. k against n.
        correlation_at_limit: Option<Vec<f64>>,
    },
}

/// One measurement beside the fitted model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Residual {
    /// Index into the measurements given to [`fit`](super::fit).
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
    /// Warnings about the data (e.g. degenerate data whose uncertainties are not meaningful);
    /// empty for a well-posed fit.
    pub warnings: Vec<String>,
    /// Free parameters, in the order given.
    pub params: Vec<Param>,
    /// Their fitted values.
    pub values: Vec<f64>,
    /// Their standard errors, `sqrt(diag(covariance))`.
    pub stderr: Vec<f64>,
    /// Whether each parameter ended inside its domain or at its bound (with an upper limit).
    pub bounds: Vec<Bound>,
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
