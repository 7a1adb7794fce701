//! The observed Stokes radiance of a surface in a scene (docs/model.md §17): its own thermal
//! emission, the sky it reflects, and the atmosphere between it and the sensor.
//!
//! At wavelength λ, for a surface at temperature T seen from `w_r`:
//! `S(w_r) = B_λ(λ, T)·ε(w_r) + ∫_H F(w, w_r)·L_sky(w) cosθ dω`, and at the sensor
//! `S_sensor = τ·S + L_path·e0`. With a uniform unpolarized sky of radiance `L_d` (`uniform`, or
//! `thermal` with `L_d = B_λ(λ, T_sky)`) the sky term is exactly `L_d·(e0 − ε)`, so
//! `S = L_d·e0 + (B_λ(T) − L_d)·ε`: the emitted and reflected polarizations cancel when
//! `B_λ(T) = L_d` (the polarization null), and the sign of S1 (the AoLP turns by 90°) flips
//! when the sky is the brighter. A tabulated sky profile takes the general sky integral
//! ([`crate::analysis::sky`]).
//!
//! Over a band the Stokes radiance is integrated, `∫ R(λ)·S(λ) dλ` (W·m⁻²·sr⁻¹), at the nodes of
//! [`crate::analysis::spectral::Spectrum::integral_nodes`]; at one wavelength it is the spectral
//! radiance (W·m⁻²·sr⁻¹·µm⁻¹). A sky's `radiance` and the path radiance are spectral radiances,
//! taken as constant across a band.
//!
//! By aspect: what a scene is made of and its checks (`description`), the observer of a
//! surface with its per-zenith terms (`observer`), the terms that depend on the view azimuth
//! (`azimuth`), the null temperature of a uniform sky (`null`); this file holds the one-call
//! entry point, [`observed_radiance`].

use crate::analysis::spectral::Spectrum;
use crate::error::{Error, Result};
use crate::model::MaterialSpec;
use std::f64::consts::FRAC_PI_2;

mod azimuth;
mod description;
mod null;
mod observer;

pub use description::{Atmosphere, Scene, SkyModel, Sun, ThermalScene};
pub use null::null_temperature;
pub use observer::{Observer, Radiance, HORIZON_MARGIN, SKY_INTEGRAL_WORK};

/// The observed Stokes radiance of `spec` in `scene` at every view `(θr, φr)` (rad) of
/// `views`, at one wavelength or integrated over a band ([`Spectrum::integral_nodes`]): an
/// [`Observer`] observing once.
///
/// # Errors
/// As [`Observer::new`]; [`Error::InvalidAngle`] for a view outside `[0, π/2)` or a
/// non-finite azimuth (with its position).
pub fn observed_radiance(
    spec: &MaterialSpec,
    scene: &ThermalScene,
    spectrum: &Spectrum,
    views: &[(f64, f64)],
) -> Result<Vec<Radiance>> {
    check_views(views)?;
    Ok(Observer::new(spec, scene, spectrum)?.observe(views))
}

/// Checks the views `(θr, φr)` (radians) of [`observed_radiance`]: θr in `[0, π/2)`, φr finite
/// and within ±[`crate::MAX_AZIMUTH_DEG`], for an adapter that builds its [`Observer`] itself
/// (to bound the work first, [`Observer::work`]).
///
/// # Errors
/// [`Error::InvalidAngle`] naming the first bad view by its index.
pub fn check_views(views: &[(f64, f64)]) -> Result<()> {
    for (i, &(t, p)) in views.iter().enumerate() {
        let (name, value, problem) = if !p.is_finite() {
            ("phi_r", p, crate::error::AngleProblem::NotFinite)
        } else if p.abs() > crate::MAX_AZIMUTH_DEG.to_radians() {
            ("phi_r", p, crate::error::AngleProblem::AzimuthTooLarge)
        } else if !(t.is_finite() && (0.0..FRAC_PI_2).contains(&t)) {
            ("theta_r", t, crate::error::AngleProblem::ViewBelowHorizon)
        } else {
            continue;
        };
        return Err(Error::InvalidAngle {
            name,
            value,
            degrees: false,
            index: Some(i),
            problem,
        });
    }
    Ok(())
}
