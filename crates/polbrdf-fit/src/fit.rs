//! The general fit: any subset of the material parameters against any mix of measured BRDF,
//! DoLP and Mueller entries, by Levenberg–Marquardt, with covariance and χ² (docs/model.md §7a).
//! Every residual vector is one call of the batch engine over the measured geometries.
//!
//! This file holds the driver [`fit`] and its settings; each of its steps has a file of its own:
//! the data and their checks, the problem (residual assembly), the minimizer's objective, the
//! starts, the refinement to the solution, the profiles of parameters at a bound, the
//! uncertainties, the result types, and the fit per wavelength.

mod covariance;
mod data;
mod objective;
mod per_wavelength;
mod problem;
mod profile;
mod refine;
mod result;
mod starts;

pub use data::{check_measurements, Measurement, Observable};
pub use per_wavelength::{fit_per_wavelength, WavelengthFit};
pub use result::{Bound, FitResult, Residual};

use crate::error::FitError;
use crate::lm::LmOptions;
use crate::params::Param;
use polbrdf::MaterialSpec;
use problem::Problem;

/// How the model is evaluated at the measured geometries.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Evaluator {
    /// The batch engine, over all geometries at once (default).
    #[default]
    Engine,
    /// `Material::evaluate_angles` one geometry at a time, on angle variables computed once —
    /// how fits were evaluated before the engine; kept to verify the engine's results and to
    /// measure the difference side by side (`cargo bench -p polbrdf-fit`).
    OneGeometry,
}

/// Settings of [`fit`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitOptions {
    /// Extra starts, scattered around the initial values (factor up to 2 each way), besides the
    /// initial values and the zero-bistatic start. The best result is kept.
    pub extra_starts: usize,
    /// Seed of the scatter.
    pub seed: u64,
    /// Stopping rules.
    pub lm: LmOptions,
    /// How the model is evaluated.
    pub evaluator: Evaluator,
}

impl Default for FitOptions {
    fn default() -> Self {
        Self {
            extra_starts: 2,
            seed: 1,
            lm: LmOptions::default(),
            evaluator: Evaluator::Engine,
        }
    }
}

/// Fits the `free` parameters of `base` to `data`.
///
/// Strictly positive parameters are fitted as `ln x`; non-negative ones (k, a, ρ_D, ρ_V) as `x`
/// with the bound `x ≥ 0`, which the minimizer respects by projected steps — so a parameter
/// the data push to 0 ends there, is reported as [`Bound::AtLowerBound`] with a one-sided upper
/// limit, and does not make the fit fail. The covariance is computed in the natural parameters
/// from a central-difference Jacobian at the solution (forward differences at a bound).
///
/// # Errors
/// [`FitError::TooFewPoints`] unless there are more measurements than free parameters;
/// [`FitError::Unidentifiable`] when the data cannot determine some parameter;
/// [`FitError::Model`] if `base` is invalid.
pub fn fit(
    base: &MaterialSpec,
    free: &[Param],
    data: &[Measurement],
    opts: &FitOptions,
) -> Result<FitResult, FitError> {
    check_request(base, free, data, opts)?;
    let problem = Problem::new(base, free, data, opts.evaluator)?;
    let (starts, zero_bistatic) = starts::start_values(base, free, data, opts)?;
    let (x, best, agreeing) = starts::best_of_starts(&problem, &starts, &opts.lm)?;
    let scaled_by_residuals = data.iter().any(|d| d.sigma.is_none());
    let solution = refine::settle(&problem, x, best, scaled_by_residuals, &opts.lm);
    let (x, best) = (solution.x, solution.best);
    let dof = data.len() - free.len();
    let reduced_chi2 = best.chi2 / dof as f64;
    let scale = if scaled_by_residuals {
        reduced_chi2
    } else {
        1.0
    };
    let uncertainties = covariance::uncertainties(&problem, &x, &solution.limits, scale)?;
    let residuals = residual_table(&problem, data, &x, scale)?;
    Ok(FitResult {
        warnings: data::degenerate_data_warnings(data, free.len()),
        params: free.to_vec(),
        spec: problem.spec_at(&x),
        values: x,
        stderr: uncertainties.stderr,
        bounds: uncertainties.bounds,
        covariance: uncertainties.covariance,
        correlation: uncertainties.correlation,
        chi2: best.chi2,
        dof,
        reduced_chi2,
        scaled_by_residuals,
        converged: best.converged,
        iterations: best.iterations,
        message: best.message,
        starts: (starts.len(), agreeing),
        zero_bistatic,
        residuals,
    })
}

/// Refuses a fit that cannot start, before anything is allocated: an invalid constant-index
/// material, no free parameter, no more measurements than free parameters, more extra starts
/// than [`crate::MAX_EXTRA_STARTS`], or a value that could overflow χ² ([`check_measurements`]).
fn check_request(
    base: &MaterialSpec,
    free: &[Param],
    data: &[Measurement],
    opts: &FitOptions,
) -> Result<(), FitError> {
    if !base.is_spectral() {
        base.build()?;
    }
    if free.is_empty() {
        return Err(FitError::BadParameterList("no free parameter".into()));
    }
    let p = free.len();
    let m = data.len();
    if m <= p {
        return Err(FitError::TooFewPoints {
            measurements: m,
            parameters: p,
        });
    }
    if opts.extra_starts > crate::MAX_EXTRA_STARTS {
        return Err(FitError::TooManyStarts(opts.extra_starts));
    }
    check_measurements(data)
}

/// Every measurement beside the model at the solution `x`: the model's value, the data, and
/// the σ used — the given one, or the one the residuals estimate, `sqrt(scale)` (χ²/dof).
///
/// # Errors
/// [`FitError::Model`] if the material cannot be built at `x`.
fn residual_table(
    problem: &Problem<'_>,
    data: &[Measurement],
    x: &[f64],
    scale: f64,
) -> Result<Vec<Residual>, FitError> {
    let material = problem.material_at(x)?;
    let sigma_scale = scale.sqrt();
    let mut model = vec![0.0; data.len()];
    problem.model_values(&material, &mut model);
    Ok(data
        .iter()
        .zip(model)
        .enumerate()
        .map(|(index, (d, model))| Residual {
            index,
            model,
            data: d.value,
            sigma: d.sigma.unwrap_or(sigma_scale),
        })
        .collect())
}
