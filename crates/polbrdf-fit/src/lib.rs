//! Parameter inversion for the simplified Maxwell–Beard pBRDF.
//!
//! - [`zbs::invert`]: the zero-bistatic inversion of eq. 5 (docs/model.md §7): from backscatter BRDF
//!   measurements and known ρ_D, ρ_V, the samples of D(θN) and `(a, b)` by weighted log-linear
//!   regression, with standard errors.
//! - [`mod@fit`]: a Levenberg–Marquardt fit of any subset of the material parameters to any mix of
//!   measured BRDF, DoLP and Mueller entries, with covariance, correlation and χ².

#![warn(missing_docs)]

pub mod error;
pub mod fit;
pub mod lm;
pub mod params;
pub mod synthetic;
pub mod zbs;

pub use error::FitError;
pub use fit::{
    check_measurements, fit, fit_per_wavelength, Bound, Evaluator, FitOptions, FitResult,
    Measurement, Observable, Residual, WavelengthFit,
};
pub use params::Param;

/// The most extra starts a fit accepts ([`FitOptions::extra_starts`]): each is a full
/// Levenberg–Marquardt run, and their start values are allocated up front.
pub const MAX_EXTRA_STARTS: usize = 10_000;

/// The largest `|value/σ|` (or `|value|` without σ) of a measurement: beyond it a squared
/// residual could overflow χ² ([`FitError::DataOutOfRange`]).
pub const MAX_WEIGHTED_VALUE: f64 = 1e100;
