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

use crate::analysis::emission::{emissivities, Emissivity};
use crate::analysis::sky::{sky_reflection, ProfileSky, ZenithProfile};
use crate::analysis::spectral::Spectrum;
use crate::analysis::thermal::{planck, temperature};
use crate::error::{Error, Result};
use crate::model::MaterialSpec;
use crate::optics::stokes::Stokes;

/// The sky of a thermal scene.
#[derive(Debug, Clone, PartialEq)]
pub enum SkyModel {
    /// No sky: nothing to reflect (`model = "none"`).
    None,
    /// A uniform unpolarized sky of spectral radiance `radiance` (W·m⁻²·sr⁻¹·µm⁻¹) at every
    /// wavelength (`model = "uniform"`).
    Uniform {
        /// Spectral radiance.
        radiance: f64,
    },
    /// A uniform unpolarized sky radiating as a blackbody at its brightness temperature
    /// (`model = "thermal"`): `L_d = B_λ(λ, T_sky)`.
    Thermal {
        /// Brightness temperature (K).
        temperature_k: f64,
    },
    /// An unpolarized sky whose spectral radiance depends on the zenith angle, tabulated
    /// (`model = "profile"`), the same at every wavelength.
    Profile(ZenithProfile),
}

impl SkyModel {
    /// The uniform radiance at `lambda_um`, `None` for a sky that is not uniform.
    fn uniform_at(&self, lambda_um: f64) -> Option<f64> {
        match self {
            SkyModel::None => Some(0.0),
            SkyModel::Uniform { radiance } => Some(*radiance),
            SkyModel::Thermal { temperature_k } => Some(planck(lambda_um, *temperature_k)),
            SkyModel::Profile(_) => None,
        }
    }
}

/// Transmittance and path radiance between the surface and the sensor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Atmosphere {
    /// Transmittance τ in `[0, 1]` (default 1).
    pub transmittance: f64,
    /// Unpolarized path spectral radiance (W·m⁻²·sr⁻¹·µm⁻¹, default 0), constant across a band.
    pub path_radiance: f64,
}

impl Default for Atmosphere {
    fn default() -> Self {
        Self {
            transmittance: 1.0,
            path_radiance: 0.0,
        }
    }
}

/// A thermal scene: the surface's temperature (no emission without one), the sky and the
/// atmosphere.
#[derive(Debug, Clone, PartialEq)]
pub struct ThermalScene {
    /// The surface temperature (K); `None`: no thermal emission.
    pub surface_temperature_k: Option<f64>,
    /// The sky.
    pub sky: SkyModel,
    /// The atmosphere.
    pub atmosphere: Atmosphere,
}

impl ThermalScene {
    /// Checks every value.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `surface.temperature_k`, `sky.radiance`,
    /// `sky.temperature_k`, `atmosphere.transmittance` or `atmosphere.path_radiance`.
    pub fn validate(&self) -> Result<()> {
        if let Some(t) = self.surface_temperature_k {
            temperature("surface.temperature_k", t)?;
        }
        match &self.sky {
            SkyModel::Uniform { radiance } => {
                crate::error::non_negative("sky.radiance", *radiance)?;
            }
            SkyModel::Thermal { temperature_k } => {
                temperature("sky.temperature_k", *temperature_k)?;
            }
            SkyModel::None | SkyModel::Profile(_) => {}
        }
        let t = self.atmosphere.transmittance;
        if !(t.is_finite() && (0.0..=1.0).contains(&t)) {
            return Err(Error::InvalidParameter {
                name: "atmosphere.transmittance",
                value: t,
                reason: "must lie in [0, 1]",
            });
        }
        crate::error::non_negative("atmosphere.path_radiance", self.atmosphere.path_radiance)?;
        Ok(())
    }

    /// The same scene with another surface temperature.
    pub fn with_surface_temperature(&self, t: Option<f64>) -> Self {
        Self {
            surface_temperature_k: t,
            ..self.clone()
        }
    }
}

/// One observed Stokes radiance with its ingredients.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Radiance {
    /// View zenith θr (rad).
    pub theta_r: f64,
    /// View azimuth φr (rad).
    pub phi_r: f64,
    /// At the sensor: `τ·(emitted + reflected) + L_path·e0`.
    pub stokes: Stokes,
    /// The emitted part `B·ε` at the surface.
    pub emitted: Stokes,
    /// The reflected sky at the surface.
    pub reflected: Stokes,
}

/// The observed Stokes radiance of `spec` in `scene` at every view `(θr, φr)` (rad) of
/// `views`, at one wavelength or integrated over a band ([`Spectrum::integral_nodes`]). The
/// emissivity is computed once per distinct view zenith and spectral node (the model is
/// isotropic).
///
/// # Errors
/// As [`ThermalScene::validate`]; [`Error::WavelengthOutOfRange`] where the band leaves a
/// spectral index's data; [`Error::InvalidAngle`] for a view at or below the horizon;
/// [`Error::InconsistentParameters`] for the `paper` form (no emissivity).
pub fn observed_radiance(
    spec: &MaterialSpec,
    scene: &ThermalScene,
    spectrum: &Spectrum,
    views: &[(f64, f64)],
) -> Result<Vec<Radiance>> {
    scene.validate()?;
    let nodes = spectrum.integral_nodes(&[spec]);
    let materials = Spectrum::materials(spec, &nodes)?;
    // Distinct view zeniths, in first-seen order.
    let mut zeniths: Vec<f64> = Vec::new();
    let mut zi = Vec::with_capacity(views.len());
    for &(t, p) in views {
        if !p.is_finite() {
            return Err(Error::InvalidAngle {
                name: "phi_r",
                value: p,
                degrees: false,
                index: Some(zi.len()),
                problem: crate::error::AngleProblem::NotFinite,
            });
        }
        let k = zeniths.iter().position(|z| *z == t).unwrap_or_else(|| {
            zeniths.push(t);
            zeniths.len() - 1
        });
        zi.push(k);
    }
    let zero = Stokes([0.0; 4]);
    let mut emitted = vec![zero; views.len()];
    let mut reflected = vec![zero; views.len()];
    let mut path = 0.0;
    for ((lambda, w), m) in nodes.iter().zip(&materials) {
        let eps: Vec<Emissivity> = emissivities(m, &zeniths)?;
        let b = scene
            .surface_temperature_k
            .map_or(0.0, |t| planck(*lambda, t));
        let uniform = scene.sky.uniform_at(*lambda);
        for (k, &(t, p)) in views.iter().enumerate() {
            let e = &eps[zi[k]].eps;
            emitted[k] = emitted[k].combine(1.0, e, w * b);
            let r = match (uniform, &scene.sky) {
                (Some(l), _) => Stokes([l * (1.0 - e.0[0]), -l * e.0[1], -l * e.0[2], -l * e.0[3]]),
                (None, SkyModel::Profile(profile)) => sky_reflection(
                    m,
                    t,
                    p,
                    &ProfileSky {
                        profile: profile.clone(),
                        scale: 1.0,
                    },
                )?,
                (None, _) => unreachable!("only a profile sky is not uniform"),
            };
            reflected[k] = reflected[k].combine(1.0, &r, *w);
        }
        path += w * scene.atmosphere.path_radiance;
    }
    let tau = scene.atmosphere.transmittance;
    Ok(views
        .iter()
        .enumerate()
        .map(|(k, &(t, p))| {
            let mut s = emitted[k].combine(tau, &reflected[k], tau);
            s.0[0] += path;
            Radiance {
                theta_r: t,
                phi_r: p,
                stokes: s,
                emitted: emitted[k],
                reflected: reflected[k],
            }
        })
        .collect())
}
