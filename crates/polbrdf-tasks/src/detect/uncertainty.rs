//! The detection range's uncertainty from the fitted materials' parameter covariances
//! (docs/detection.md, "Uncertainty of the range"): `σ_R² = J·Σ·Jᵀ` by the core's
//! [`propagate`] (central differences, step a tenth of each parameter's σ), over the target's
//! and the background's free parameters together. The two fits are independent measurements:
//! their joint covariance is block-diagonal.
//!
//! Each perturbed parameter set is a new material, observed at the view again (over the same
//! spectrum and with the same quality as the study) and searched for its detection range; a
//! material left unperturbed keeps the study's observation, so the range at the fitted
//! parameters is the study's, bit for bit. A view costs `2·n + 1` range searches and `2·n`
//! observations (`n` the free parameters of both fits): only the best-ranked views get an
//! interval by default ([`DEFAULT_UNCERTAINTY_VIEWS`]), every view on request.

use super::study::{RangeUncertainty, ViewResult};
use crate::fit_covariance::FitCovariance;
use crate::spectrum::NamedMaterial;
use crate::TaskResult;
use polbrdf::analysis::detection::statistics::phi_inv;
use polbrdf::analysis::detection::uncertainty::propagate;
use polbrdf::analysis::detection::{Detector, MaxRange};
use polbrdf::analysis::scene::Observer;
use polbrdf::analysis::sky::Quality;
use polbrdf::{Spectrum, Stokes};
use polbrdf_fit::Param;
use polbrdf_io::Scene;

/// The views given an interval by default: the best-ranked ten.
pub const DEFAULT_UNCERTAINTY_VIEWS: usize = 10;

/// The confidence of the reported interval.
pub const CONFIDENCE: f64 = 0.95;

/// The `z` of the interval `R ± z·σ_R`: `Φ⁻¹(½ + CONFIDENCE/2)` (1.959963984540054 for 95 %),
/// the normal quantile — the interval is the linearization's, of a range taken as normal.
pub fn z() -> f64 {
    phi_inv(0.5 + 0.5 * CONFIDENCE)
}

/// The fits of a study and what their propagation needs of it.
pub(crate) struct Propagation<'a> {
    pub detector: &'a Detector,
    pub scene: &'a Scene,
    /// The target and the background.
    pub materials: [&'a NamedMaterial; 2],
    /// Their fits.
    pub fits: [Option<&'a FitCovariance>; 2],
    /// The spectrum observed over, and the factor observations are scaled by.
    pub spectrum: &'a Spectrum,
    pub scale: f64,
    pub quality: Quality,
}

/// Whether `v` lies in `p`'s domain (> 0 for the strictly positive parameters, ≥ 0 for the
/// others).
fn in_domain(p: Param, v: f64) -> bool {
    v.is_finite()
        && if p.strictly_positive() {
            v > 0.0
        } else {
            v >= 0.0
        }
}

impl Propagation<'_> {
    /// The joint parameters (the target's, then the background's) and their block-diagonal
    /// covariance.
    fn joint(&self) -> (Vec<f64>, Vec<f64>) {
        let fits: Vec<&FitCovariance> = self.fits.iter().flatten().copied().collect();
        let n: usize = fits.iter().map(|f| f.params.len()).sum();
        let mut params = Vec::with_capacity(n);
        let mut cov = vec![0.0; n * n];
        for f in fits {
            let (o, m) = (params.len(), f.params.len());
            for i in 0..m {
                for j in 0..m {
                    cov[(o + i) * n + o + j] = f.covariance[i * m + j];
                }
            }
            params.extend_from_slice(&f.values);
        }
        (params, cov)
    }

    /// Material `k`'s Stokes radiance at the view with its fit's parameters at `values`: the
    /// study's when they are the fitted ones; `None` outside a parameter's domain or where the
    /// material is refused.
    fn stokes(&self, k: usize, values: &[f64], view: &ViewResult) -> Option<Stokes> {
        let stored = if k == 0 { view.target } else { view.background };
        let Some(fit) = self.fits[k] else {
            return Some(stored);
        };
        if values == fit.values.as_slice() {
            return Some(stored);
        }
        let mut spec = self.materials[k].spec.clone();
        for (p, v) in fit.params.iter().zip(values) {
            if !in_domain(*p, *v) {
                return None;
            }
            p.set(&mut spec, *v);
        }
        let surface = if k == 0 {
            &self.scene.target
        } else {
            &self.scene.background
        };
        let thermal = self
            .scene
            .thermal
            .with_surface_temperature(surface.temperature_k);
        let observer = Observer::new(&spec, &thermal, self.spectrum).ok()?;
        let r = observer.observe_with(&[(view.theta_r, view.phi_r)], self.quality);
        Some(Stokes(r[0].stokes.0.map(|x| x * self.scale)))
    }

    /// The view's detection range with its uncertainty; `None` when it has no range.
    ///
    /// # Errors
    /// As the range search ([`Detector::max_range`]).
    pub fn of_view(&self, view: &ViewResult) -> TaskResult<Option<RangeUncertainty>> {
        let Some(MaxRange::At { .. }) = view.max_range else {
            return Ok(None);
        };
        let (params, cov) = self.joint();
        let nt = self.fits[0].map_or(0, |f| f.params.len());
        let f = |p: &[f64]| -> polbrdf::Result<Option<f64>> {
            let (Some(t), Some(b)) = (
                self.stokes(0, &p[..nt], view),
                self.stokes(1, &p[nt..], view),
            ) else {
                return Ok(None);
            };
            Ok(match self.detector.max_range(&t, &b, view.theta_r)? {
                MaxRange::At { range_m, .. } => Some(range_m),
                _ => None,
            })
        };
        Ok(Some(match propagate(f, &params, &cov)? {
            Some(p) => {
                let z = z();
                RangeUncertainty::Interval {
                    sigma_m: p.sigma,
                    lo_m: (p.value - z * p.sigma).max(0.0),
                    hi_m: p.value + z * p.sigma,
                }
            }
            None => RangeUncertainty::Undefined,
        }))
    }
}
