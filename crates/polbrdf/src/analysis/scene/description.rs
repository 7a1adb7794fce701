//! What a scene is made of — the surface's temperature, the sky, the sun and the atmosphere —
//! and the check of every value.

use crate::analysis::sky::{ClearSky, TableSky, ZenithProfile};
use crate::analysis::thermal::{planck, temperature};
use crate::error::{Error, Result};
use crate::optics::stokes::Stokes;
use std::f64::consts::{FRAC_PI_2, PI};

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
    /// The CIE standard clear sky with Rayleigh polarization (`model = "cie-clear"`,
    /// [`ClearSky`]) for the scene's sun, scaled to a horizontal (spectral) irradiance, the same
    /// at every wavelength. Needs a [`Sun`] for its position.
    ClearSky {
        /// The sky's horizontal irradiance `∫_H L cosθ dω` (W·m⁻²·µm⁻¹).
        irradiance: f64,
        /// The maximum degree of polarization δ_max (90° from the sun), in [0, 1].
        dop_max: f64,
    },
    /// A tabulated Stokes sky (`model = "table"`, [`TableSky`]), the same at every wavelength.
    Table(TableSky),
}

impl SkyModel {
    /// The uniform radiance at `lambda_um`, `None` for a sky that is not uniform.
    pub(super) fn uniform_at(&self, lambda_um: f64) -> Option<f64> {
        match self {
            SkyModel::None => Some(0.0),
            SkyModel::Uniform { radiance } => Some(*radiance),
            SkyModel::Thermal { temperature_k } => Some(planck(lambda_um, *temperature_k)),
            SkyModel::Profile(_) | SkyModel::ClearSky { .. } | SkyModel::Table(_) => None,
        }
    }

    /// Whether the sky is the same at every azimuth.
    pub fn is_azimuth_independent(&self) -> bool {
        !matches!(self, SkyModel::ClearSky { .. } | SkyModel::Table(_))
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

/// The sun: a collimated source from `(zenith, azimuth)` of irradiance `irradiance` on a
/// plane normal to its beam (W·m⁻²·µm⁻¹, the same at every wavelength) and Stokes vector
/// `stokes` (in the arriving beam's psps basis, normalized to `s0 = 1`). Its contribution to
/// the observed radiance is `E·cosθs·F(w_s, w_r)·s` (docs/model.md §18).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sun {
    /// Zenith angle (rad), in `[0, π/2)`.
    pub zenith: f64,
    /// Azimuth (rad).
    pub azimuth: f64,
    /// Irradiance normal to the beam (≥ 0).
    pub irradiance: f64,
    /// Stokes vector, `s0 = 1` (unpolarized: `(1, 0, 0, 0)`).
    pub stokes: Stokes,
}

impl Sun {
    /// The default azimuth of the sun (rad) when a scene gives only its zenith angle.
    pub const DEFAULT_AZIMUTH: f64 = 0.0;

    /// An unpolarized sun.
    pub fn unpolarized(zenith: f64, azimuth: f64, irradiance: f64) -> Self {
        Self {
            zenith,
            azimuth,
            irradiance,
            stokes: Stokes::unpolarized(),
        }
    }
}

/// A scene: the surface's temperature (no emission without one), the sun (none by default),
/// the sky and the atmosphere.
#[derive(Debug, Clone, PartialEq)]
pub struct ThermalScene {
    /// The surface temperature (K); `None`: no thermal emission.
    pub surface_temperature_k: Option<f64>,
    /// The sky.
    pub sky: SkyModel,
    /// The atmosphere.
    pub atmosphere: Atmosphere,
    /// The sun; `None`: no collimated source.
    pub sun: Option<Sun>,
}

/// Another name for [`ThermalScene`], which holds daylight scenes as well.
pub type Scene = ThermalScene;

impl ThermalScene {
    /// Checks every value.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `surface.temperature_k`, `sun.zenith_deg` (the sun
    /// must be above the horizon), `sun.azimuth_deg` (finite, |φs| ≤ [`crate::MAX_AZIMUTH_DEG`]
    /// as every azimuth), `sun.irradiance`, `sun.stokes`,
    /// `sky.radiance`, `sky.temperature_k`, `sky.irradiance`, `sky.dop_max`,
    /// `atmosphere.transmittance` or `atmosphere.path_radiance` (radiances and irradiances
    /// finite, ≥ 0 and at most 1e150); [`Error::InconsistentParameters`] for a cie-clear sky
    /// without a sun.
    pub fn validate(&self) -> Result<()> {
        if let Some(t) = self.surface_temperature_k {
            temperature("surface.temperature_k", t)?;
        }
        if let Some(sun) = &self.sun {
            if !(sun.zenith.is_finite() && (0.0..FRAC_PI_2).contains(&sun.zenith)) {
                return Err(Error::InvalidParameter {
                    name: "sun.zenith_deg",
                    value: sun.zenith.to_degrees(),
                    reason: "the sun must be above the horizon: in [0, 90) degrees",
                });
            }
            if !(sun.azimuth.is_finite()
                && sun.azimuth.abs() <= crate::MAX_AZIMUTH_DEG.to_radians())
            {
                return Err(Error::InvalidParameter {
                    name: "sun.azimuth_deg",
                    value: sun.azimuth.to_degrees(),
                    reason: "must be finite and at most 1e8 degrees in magnitude \
                             (polbrdf::MAX_AZIMUTH_DEG)",
                });
            }
            crate::error::radiometric("sun.irradiance", sun.irradiance)?;
            let st = sun.stokes.0;
            if st.iter().any(|v| !v.is_finite())
                || (st[0] - 1.0).abs() > 1e-12
                || st[1].hypot(st[2]).hypot(st[3]) > 1.0 + 1e-9
            {
                return Err(Error::InvalidParameter {
                    name: "sun.stokes",
                    value: st[0],
                    reason: "must be finite, normalized to s0 = 1 and of degree of \
                             polarization at most 1",
                });
            }
        }
        match &self.sky {
            SkyModel::Uniform { radiance } => {
                crate::error::radiometric("sky.radiance", *radiance)?;
            }
            SkyModel::Thermal { temperature_k } => {
                temperature("sky.temperature_k", *temperature_k)?;
            }
            SkyModel::ClearSky {
                irradiance,
                dop_max,
            } => {
                let Some(sun) = &self.sun else {
                    return Err(Error::InconsistentParameters(
                        "the cie-clear sky needs a sun ([sun] zenith_deg, azimuth_deg): its \
                         radiance and polarization are set by the sun's position"
                            .into(),
                    ));
                };
                ClearSky::new(sun.zenith, sun.azimuth, *irradiance, *dop_max)?;
            }
            SkyModel::None | SkyModel::Profile(_) | SkyModel::Table(_) => {}
        }
        let t = self.atmosphere.transmittance;
        if !(t.is_finite() && (0.0..=1.0).contains(&t)) {
            return Err(Error::InvalidParameter {
                name: "atmosphere.transmittance",
                value: t,
                reason: "must lie in [0, 1]",
            });
        }
        crate::error::radiometric("atmosphere.path_radiance", self.atmosphere.path_radiance)?;
        Ok(())
    }

    /// Whether what a surface observes here is the same at every view azimuth: no sun and an
    /// azimuth-independent sky (the model is isotropic).
    pub fn is_azimuth_independent(&self) -> bool {
        self.sun.is_none() && self.sky.is_azimuth_independent()
    }

    /// The same scene with the sun's azimuth taken into `[0, 2π)` when it lies outside
    /// `[−2π, 2π]` (the same direction): the views folded about the sun's vertical plane then
    /// stay within a turn of it, inside [`crate::MAX_AZIMUTH_DEG`], however large the sun's
    /// azimuth (a sun at the bound itself put a folded view beyond it: issue 35). Azimuths
    /// within a turn are kept as given, bit for bit.
    pub(super) fn with_sun_azimuth_reduced(&self) -> Self {
        let mut scene = self.clone();
        if let Some(sun) = scene.sun.as_mut() {
            if sun.azimuth.abs() > 2.0 * PI {
                sun.azimuth = sun.azimuth.rem_euclid(2.0 * PI);
            }
        }
        scene
    }

    /// The same scene with another surface temperature.
    pub fn with_surface_temperature(&self, t: Option<f64>) -> Self {
        Self {
            surface_temperature_k: t,
            ..self.clone()
        }
    }
}
