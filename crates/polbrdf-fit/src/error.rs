//! Why a fit can refuse to give an answer.

/// Errors of the inversion. Each says what is wrong and what would fix it.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum FitError {
    /// A name in the free-parameter list is not a parameter.
    #[error("unknown parameter `{0}` (fittable: n, k, a, b, sigma_deg, rho_d, rho_v, tau_deg, omega_deg)")]
    UnknownParameter(String),
    /// The free-parameter list is unusable (empty, repeated, `b` with `sigma_deg`…).
    #[error("{0}")]
    BadParameterList(String),
    /// Fewer measurements than free parameters (or none).
    #[error("too few measurements: {measurements} value(s) for {parameters} free parameter(s); need more values than parameters")]
    TooFewPoints {
        /// Number of measured values.
        measurements: usize,
        /// Number of free parameters.
        parameters: usize,
    },
    /// The data cannot determine these parameters (their Jacobian columns are (nearly) zero or
    /// linearly dependent at the solution).
    #[error("parameter(s) {0} cannot be determined from these data (no sensitivity, or fully correlated with others); fix them in the material file or add measurements that depend on them")]
    Unidentifiable(String),
    /// The model, at some parameter values, is invalid (e.g. a start value out of range).
    #[error("invalid model parameters: {0}")]
    Model(#[from] polbrdf::Error),
    /// More extra starts than [`crate::MAX_EXTRA_STARTS`].
    #[error("{0} extra starts: at most {max} (each start is a full fit)", max = crate::MAX_EXTRA_STARTS)]
    TooManyStarts(usize),
    /// A measurement is so large (value/σ beyond 1e100) that χ² overflows: an outlier or a
    /// unit error in the data, not in the parameters. `index` counts the measurements given.
    #[error("measurement {index} ({observable} = {value:e}, σ = {sigma}) is too large for a least-squares fit: |value/σ| > 1e100 makes χ² overflow (an outlier or a unit error in the data?)")]
    DataOutOfRange {
        /// Index of the measurement in the data given to the fit.
        index: usize,
        /// Its observable's name.
        observable: String,
        /// Its value.
        value: f64,
        /// Its σ (1 when none was given).
        sigma: f64,
    },
    /// The zero-bistatic inversion has too few usable backscatter points.
    #[error("zero-bistatic inversion: {0}")]
    ZeroBistatic(String),
}
