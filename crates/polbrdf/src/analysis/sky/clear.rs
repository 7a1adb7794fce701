//! The CIE standard clear sky with Rayleigh single-scattering polarization (docs/model.md §18):
//! its radiance and DoLP formulas and the integral that scales it to a horizontal irradiance.

use super::basis::{cross, dot, linear_stokes_of};
use super::{direction, SkyRadiance};
use crate::analysis::facets::smoothstep_n;
use crate::error::{Error, Result};
use crate::optics::stokes::Stokes;
use std::f64::consts::{FRAC_PI_2, PI};

/// The CIE standard clear sky (ISO 15469 / CIE S 011, type 12) with Rayleigh single-scattering
/// polarization (docs/model.md §18).
///
/// Radiance `L(Z, γ) = scale·f(γ)·φ(Z)` with `φ(Z) = 1 + a·exp(b/cos Z)` (φ = 1 at the
/// horizon) and `f(γ) = 1 + c·(exp(dγ) − exp(dπ/2)) + e·cos²γ`, `a = −1, b = −0.32, c = 10,
/// d = −3, e = 0.45`; Z the zenith angle of the sky point, γ its angle from the sun. `scale`
/// makes the horizontal irradiance `∫_H L cosθ dω` the given one. DoLP
/// `δ_max·sin²γ/(1 + cos²γ)`, electric vector along `w × w_s` (perpendicular to the plane of
/// sun, sky point and observer), in the arriving beam's basis ([`linear_stokes`](super::linear_stokes)).
#[derive(Debug, Clone, PartialEq)]
pub struct ClearSky {
    sun_zenith: f64,
    sun_azimuth: f64,
    sun: [f64; 3],
    scale: f64,
    dop_max: f64,
}

impl ClearSky {
    /// The default maximum degree of polarization δ_max of the clear sky (90° from the sun),
    /// written only here: the scene files' `dop_max` and the Python module's take it.
    pub const DEFAULT_DOP_MAX: f64 = 0.75;

    /// The parameters `(a, b, c, d, e)` of CIE sky type 12 (clear, low turbidity).
    pub const CIE12: (f64, f64, f64, f64, f64) = (-1.0, -0.32, 10.0, -3.0, 0.45);

    /// A clear sky for the sun at `(sun_zenith, sun_azimuth)` (rad; the sun may be anywhere on
    /// the upper hemisphere, its zenith angle in `[0, π/2]`), scaled to the horizontal
    /// irradiance `irradiance` (≥ 0, any unit: the sky's radiance is in that unit per sr), with
    /// the maximum degree of polarization `dop_max` in `[0, 1]`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `sun.zenith_deg`, `sun.azimuth_deg`,
    /// `sky.irradiance` or `sky.dop_max`.
    pub fn new(sun_zenith: f64, sun_azimuth: f64, irradiance: f64, dop_max: f64) -> Result<Self> {
        if !(sun_zenith.is_finite() && (0.0..=FRAC_PI_2).contains(&sun_zenith)) {
            return Err(Error::InvalidParameter {
                name: "sun.zenith_deg",
                value: sun_zenith.to_degrees(),
                reason: "the sun of a clear sky must be above the horizon: in [0, 90] degrees",
            });
        }
        if !sun_azimuth.is_finite() {
            return Err(Error::InvalidParameter {
                name: "sun.azimuth_deg",
                value: sun_azimuth,
                reason: "must be finite",
            });
        }
        crate::error::radiometric("sky.irradiance", irradiance)?;
        if !(dop_max.is_finite() && (0.0..=1.0).contains(&dop_max)) {
            return Err(Error::InvalidParameter {
                name: "sky.dop_max",
                value: dop_max,
                reason: "must lie in [0, 1]",
            });
        }
        let mut sky = Self {
            sun_zenith,
            sun_azimuth,
            sun: direction(sun_zenith, sun_azimuth),
            scale: 1.0,
            dop_max,
        };
        let relative = sky.relative_irradiance();
        sky.scale = irradiance / relative;
        Ok(sky)
    }

    /// `f(γ)·φ(Z)` toward `(theta, phi)`.
    pub fn relative_radiance(&self, theta: f64, phi: f64) -> f64 {
        self.relative_at(&direction(theta, phi)).0
    }

    /// `(f(γ)·φ(Z), cosγ)` toward the unit vector `w`: the one place the CIE formula is written.
    fn relative_at(&self, w: &[f64; 3]) -> (f64, f64) {
        let (a, b, c, d, e) = Self::CIE12;
        let cg = dot(w, &self.sun).clamp(-1.0, 1.0);
        let f = 1.0 + c * ((d * cg.acos()).exp() - (d * FRAC_PI_2).exp()) + e * cg * cg;
        let ct = w[2];
        let grad = if ct > 0.0 {
            1.0 + a * (b / ct).exp()
        } else {
            1.0
        };
        (f * grad, cg)
    }

    /// `∫_H f(γ)·φ(Z) cosθ dω` on a product rule with the sun at a panel corner
    /// ([`relative_irradiance_with`] with 4 panels of 16 points per segment): converged to
    /// 1e-11 relative (`tests/daylight.rs`).
    pub fn relative_irradiance(&self) -> f64 {
        relative_irradiance_with(self, 4, 16)
    }

    /// The radiance factor: `L = scale·f(γ)·φ(Z)`.
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// The sun's zenith angle and azimuth (rad).
    pub fn sun(&self) -> (f64, f64) {
        (self.sun_zenith, self.sun_azimuth)
    }

    /// `δ_max`.
    pub fn dop_max(&self) -> f64 {
        self.dop_max
    }

    /// The Rayleigh DoLP `δ_max·sin²γ/(1 + cos²γ)` at angle `gamma` from the sun.
    pub fn dolp_at(&self, gamma: f64) -> f64 {
        self.dolp_of_cos(gamma.cos())
    }

    /// [`ClearSky::dolp_at`] of `cosγ`.
    fn dolp_of_cos(&self, c: f64) -> f64 {
        self.dop_max * (1.0 - c * c) / (1.0 + c * c)
    }
}

/// `∫_H f(γ)·φ(Z) cosθ dω` of `sky`: θ in two segments split at the sun's zenith angle, φ in
/// two split at the sun's azimuth and the opposite one, each segment on `panels` smoothstep
/// Gauss–Legendre panels of `points` points — the sun, the integrand's one cone point, at a
/// panel corner where the smoothstep map clusters the nodes.
pub fn relative_irradiance_with(sky: &ClearSky, panels: usize, points: usize) -> f64 {
    let (zs, azs) = (sky.sun_zenith, sky.sun_azimuth);
    let thetas: Vec<(f64, f64)> = [(0.0, zs), (zs, FRAC_PI_2)]
        .iter()
        .filter(|(a, b)| b > a)
        .flat_map(|&(a, b)| smoothstep_n(a, b, panels, points))
        .collect();
    let phis: Vec<(f64, f64)> = [(azs, azs + PI), (azs + PI, azs + 2.0 * PI)]
        .iter()
        .flat_map(|&(a, b)| smoothstep_n(a, b, panels, points))
        .collect();
    thetas
        .iter()
        .map(|&(t, wt)| {
            let (st, ct) = t.sin_cos();
            let ring: f64 = phis
                .iter()
                .map(|&(p, wp)| wp * sky.relative_radiance(t, p))
                .sum();
            wt * ct * st * ring
        })
        .sum()
}

impl SkyRadiance for ClearSky {
    fn azimuth_origin(&self) -> f64 {
        self.sun_azimuth
    }

    fn cone_point(&self) -> Option<(f64, f64)> {
        Some((self.sun_zenith, self.sun_azimuth))
    }

    /// [`ClearSky::relative_radiance`] times `scale`, with [`ClearSky::dolp_at`] along
    /// `w × w_s` ([`linear_stokes`](super::linear_stokes)); the direction's trigonometric functions taken once (this
    /// runs at every node of every sky integral).
    fn stokes(&self, theta: f64, phi: f64) -> Stokes {
        let (st, ct) = theta.sin_cos();
        let (sp, cp) = phi.sin_cos();
        let w = [st * cp, st * sp, ct];
        let (rel, cg) = self.relative_at(&w);
        linear_stokes_of(
            self.scale * rel,
            self.dolp_of_cos(cg),
            &cross(&w, &self.sun),
            &w,
            sp,
            cp,
        )
    }
}
