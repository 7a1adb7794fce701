//! The start values of a fit and the minimization from every one of them: the material's
//! values, the zero-bistatic inversion's roughness, and starts scattered around the material's
//! values (docs/model.md §7a, "Starts").

use super::problem::Problem;
use super::{FitOptions, Measurement, Observable};
use crate::error::FitError;
use crate::lm::{LmOptions, LmReport};
use crate::params::Param;
use crate::zbs::{self, ZbsFit, ZbsPoint};
use polbrdf::sample::SplitMix64;
use polbrdf::MaterialSpec;
use rayon::prelude::*;

/// Every start of a fit of the `free` parameters of `base` to `data`: the material's values
/// (a non-negative parameter at exactly 0 at its typical magnitude instead), the zero-bistatic
/// start when it differs from them, and `opts.extra_starts` scattered ones — and the
/// zero-bistatic inversion, when the data allowed one.
///
/// # Errors
/// [`FitError::Model`] when `base` is invalid (a parameter's value cannot be read).
pub(super) fn start_values(
    base: &MaterialSpec,
    free: &[Param],
    data: &[Measurement],
    opts: &FitOptions,
) -> Result<(Vec<Vec<f64>>, Option<ZbsFit>), FitError> {
    let initial = initial_values(base, free)?;
    let mut starts = vec![initial.clone()];
    let zero_bistatic = zero_bistatic_start(base, free, data);
    if let Some(z) = &zero_bistatic {
        let mut s = initial.clone();
        for (k, param) in free.iter().enumerate() {
            match param {
                Param::B => s[k] = z.b,
                Param::SigmaDeg => s[k] = z.b.sqrt().recip().to_degrees(),
                Param::A => s[k] = z.a,
                _ => {}
            }
        }
        if s != initial {
            starts.push(s);
        }
    }
    let mut rng = SplitMix64::new(opts.seed);
    for _ in 0..opts.extra_starts {
        // A factor 2^(±1) on each value.
        starts.push(
            initial
                .iter()
                .map(|v| v * 2f64.powf(2.0 * rng.next_f64() - 1.0))
                .collect(),
        );
    }
    Ok((starts, zero_bistatic))
}

/// The material's values of the `free` parameters; a non-negative one at exactly 0 at its
/// typical magnitude instead.
fn initial_values(base: &MaterialSpec, free: &[Param]) -> Result<Vec<f64>, FitError> {
    free.iter()
        .map(|p| {
            let v = p.value(base)?;
            // At exactly 0 the gradient of a non-negative parameter can vanish (the model is
            // even in k): start at its typical magnitude instead.
            Ok(if !p.strictly_positive() && v == 0.0 {
                p.typical_scale()
            } else {
                v
            })
        })
        .collect()
}

/// Minimizes from every start (in parallel): the best result (the lowest finite χ²), and how
/// many starts reached it to 1e-6 (relative, or absolute below χ² = 1).
///
/// # Errors
/// [`FitError::Model`] when the model could not be evaluated from any start.
pub(super) fn best_of_starts(
    problem: &Problem<'_>,
    starts: &[Vec<f64>],
    lm: &LmOptions,
) -> Result<(Vec<f64>, LmReport, usize), FitError> {
    let reports: Vec<(Vec<f64>, LmReport)> = starts
        .par_iter()
        .map(|s| problem.minimize(s, &[], lm))
        .collect();
    let (x, best) = reports
        .iter()
        .filter(|r| r.1.chi2.is_finite())
        .min_by(|a, b| a.1.chi2.total_cmp(&b.1.chi2))
        .cloned()
        .ok_or_else(|| {
            FitError::Model(polbrdf::Error::InconsistentParameters(
                "the model could not be evaluated from any start".into(),
            ))
        })?;
    let agreeing = reports
        .iter()
        .filter(|r| r.1.chi2 - best.chi2 <= 1e-6 * best.chi2.max(1.0))
        .count();
    Ok((x, best, agreeing))
}

/// Runs the zero-bistatic inversion when the roughness is free and the data hold at least three
/// backscatter BRDF measurements.
fn zero_bistatic_start(
    base: &MaterialSpec,
    free: &[Param],
    data: &[Measurement],
) -> Option<ZbsFit> {
    if base.is_spectral() || !free.iter().any(|p| matches!(p, Param::B | Param::SigmaDeg)) {
        return None;
    }
    let points: Vec<ZbsPoint> = data
        .iter()
        .filter(|d| d.observable == Observable::Brdf)
        .filter_map(|d| {
            let v = d.geometry.angle_variables()?;
            (v.beta.abs() < 1e-6).then_some(ZbsPoint {
                theta: 0.5 * (v.theta_i + v.theta_r),
                f: d.value,
                sigma: d.sigma,
            })
        })
        .collect();
    let index = polbrdf::RefractiveIndex::new(base.n, base.k).ok()?;
    zbs::invert(&points, index, base.rho_d, base.rho_v).ok()
}
