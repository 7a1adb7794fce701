//! Scattering geometry (spec §1) and the angle variables of the model (eqs. 1–3, 11).
//!
//! Directions point **away** from the surface: `w = (sinθ cosφ, sinθ sinφ, cosθ)`, toward the
//! source (`w_i`) or the detector (`w_r`). The facet normal is the half vector
//! `h = unit(w_i + w_r)`.

use crate::error::{Error, Result};
use std::f64::consts::{FRAC_PI_2, PI};

/// π/2 − `FRAC_PI_2` (the rounding error of `FRAC_PI_2`).
const PIO2_LO: f64 = 6.123233995736766e-17;

/// One illumination/viewing geometry in radians (the θi, Φi, θr, Φr of eq. 1).
///
/// Construct it with [`Geometry::new`] or [`Geometry::from_degrees`], which reject NaN/∞ and
/// zenith angles outside `[0, π]`. Zenith angles `≥ π/2` are valid: such a direction is at or
/// below the horizon and the model returns the zero matrix there (spec §1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Geometry {
    theta_i: f64,
    phi_i: f64,
    theta_r: f64,
    phi_r: f64,
}

fn check_zenith(name: &'static str, value: f64, index: Option<usize>) -> Result<f64> {
    if !value.is_finite() {
        return Err(Error::InvalidAngle {
            name,
            value,
            index,
            reason: "must be finite",
        });
    }
    if !(0.0..=PI).contains(&value) {
        return Err(Error::InvalidAngle {
            name,
            value,
            index,
            reason: "zenith angle must lie in [0, π] rad ([0°, 180°])",
        });
    }
    Ok(value + 0.0)
}

fn check_azimuth(name: &'static str, value: f64, index: Option<usize>) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::InvalidAngle {
            name,
            value,
            index,
            reason: "must be finite",
        })
    }
}

impl Geometry {
    /// A geometry from zenith and azimuth angles in radians.
    ///
    /// # Errors
    /// [`Error::InvalidAngle`] for NaN/∞ or a zenith angle outside `[0, π]`.
    pub fn new(theta_i: f64, phi_i: f64, theta_r: f64, phi_r: f64) -> Result<Self> {
        Self::checked(theta_i, phi_i, theta_r, phi_r, None)
    }

    /// For callers that validated the angles already (the batch API).
    pub(crate) fn new_unchecked(theta_i: f64, phi_i: f64, theta_r: f64, phi_r: f64) -> Self {
        // `+ 0.0` turns −0.0 into +0.0, as the checked constructor does.
        Self {
            theta_i: theta_i + 0.0,
            phi_i,
            theta_r: theta_r + 0.0,
            phi_r,
        }
    }

    pub(crate) fn checked(
        theta_i: f64,
        phi_i: f64,
        theta_r: f64,
        phi_r: f64,
        index: Option<usize>,
    ) -> Result<Self> {
        Ok(Self {
            theta_i: check_zenith("theta_i", theta_i, index)?,
            phi_i: check_azimuth("phi_i", phi_i, index)?,
            theta_r: check_zenith("theta_r", theta_r, index)?,
            phi_r: check_azimuth("phi_r", phi_r, index)?,
        })
    }

    /// A geometry from angles in degrees (as in files and on the command line).
    ///
    /// # Errors
    /// As [`Geometry::new`], with the error naming the `_deg` angle and its value in degrees.
    pub fn from_degrees(
        theta_i_deg: f64,
        phi_i_deg: f64,
        theta_r_deg: f64,
        phi_r_deg: f64,
    ) -> Result<Self> {
        let rename = |e: Error| match e {
            Error::InvalidAngle {
                name,
                index,
                reason,
                ..
            } => {
                let (name, value) = match name {
                    "theta_i" => ("theta_i_deg", theta_i_deg),
                    "phi_i" => ("phi_i_deg", phi_i_deg),
                    "theta_r" => ("theta_r_deg", theta_r_deg),
                    _ => ("phi_r_deg", phi_r_deg),
                };
                let reason = if reason.starts_with("zenith") {
                    "zenith angle must lie in [0°, 180°]"
                } else {
                    reason
                };
                Error::InvalidAngle {
                    name,
                    value,
                    index,
                    reason,
                }
            }
            other => other,
        };
        Self::new(
            theta_i_deg.to_radians(),
            phi_i_deg.to_radians(),
            theta_r_deg.to_radians(),
            phi_r_deg.to_radians(),
        )
        .map_err(rename)
    }

    /// In-plane specular geometry: `θr = θi`, `φr = φi + π` (spec §1).
    ///
    /// # Errors
    /// As [`Geometry::new`].
    pub fn specular(theta: f64, phi: f64) -> Result<Self> {
        Self::new(theta, phi, theta, phi + PI)
    }

    /// Retro-reflection (backscatter, zero bistatic angle): `θr = θi`, `φr = φi` (spec §1, §6).
    ///
    /// # Errors
    /// As [`Geometry::new`].
    pub fn backscatter(theta: f64, phi: f64) -> Result<Self> {
        Self::new(theta, phi, theta, phi)
    }

    /// Incidence zenith angle θi (rad).
    pub fn theta_i(&self) -> f64 {
        self.theta_i
    }
    /// Incidence azimuth φi (rad).
    pub fn phi_i(&self) -> f64 {
        self.phi_i
    }
    /// Viewing zenith angle θr (rad).
    pub fn theta_r(&self) -> f64 {
        self.theta_r
    }
    /// Viewing azimuth φr (rad).
    pub fn phi_r(&self) -> f64 {
        self.phi_r
    }

    /// True when both directions are strictly above the horizon (`θ < π/2`, spec §1).
    pub fn is_above_horizon(&self) -> bool {
        self.theta_i < FRAC_PI_2 && self.theta_r < FRAC_PI_2
    }

    /// The same geometry with both azimuths turned by `delta` (rad). The model is invariant
    /// under this rotation (spec §7).
    pub fn rotated(&self, delta: f64) -> Self {
        Self {
            phi_i: self.phi_i + delta,
            phi_r: self.phi_r + delta,
            ..*self
        }
    }

    /// The source and detector exchanged (the reciprocal geometry).
    pub fn reciprocal(&self) -> Self {
        Self {
            theta_i: self.theta_r,
            phi_i: self.phi_r,
            theta_r: self.theta_i,
            phi_r: self.phi_i,
        }
    }

    /// Unit vector toward the source, `w_i` (spec §1).
    pub fn w_i(&self) -> [f64; 3] {
        direction(self.theta_i, self.phi_i)
    }

    /// Unit vector toward the detector, `w_r` (spec §1).
    pub fn w_r(&self) -> [f64; 3] {
        direction(self.theta_r, self.phi_r)
    }

    /// The model's angle variables for this geometry (θN, β, ΦN of eqs. 1–3 and the signed
    /// Priest–Meier rotation angles η_i, η_r of eq. 11), or `None` when a direction is at or
    /// below the horizon.
    ///
    /// Computed in closed form (spec §3), arranged to stay accurate near β → 0 and θ → 0:
    /// with Δ = φr − φi,
    /// `sin2β·cos η_i = sin(θi − θr) + 2 cosθi sinθr sin²(Δ/2)`, `sin2β·sin η_i = sinθr sinΔ`,
    /// `sin2β·cos η_r = sin(θr − θi) + 2 sinθi cosθr sin²(Δ/2)`, `sin2β·sin η_r = sinθi sinΔ`.
    pub fn angle_variables(&self) -> Option<AngleVariables> {
        if !self.is_above_horizon() {
            return None;
        }
        let (si, ci) = self.theta_i.sin_cos();
        let (sr, cr) = self.theta_r.sin_cos();
        let delta = self.phi_r - self.phi_i;
        let (sd, _) = delta.sin_cos();
        let half = (0.5 * delta).sin();
        let vers = 2.0 * half * half; // 1 − cosΔ, without cancellation
        let sin_dif = (self.theta_i - self.theta_r).sin();

        // Signed facet-frame rotation angles (unnormalized cos/sin pairs share the norm sin2β).
        let ci_n = sin_dif + ci * sr * vers;
        let si_n = sr * sd;
        let cr_n = -sin_dif + si * cr * vers;
        let sr_n = si * sd;
        let sin_2beta = ci_n.hypot(si_n);

        // cos2β = w_i·w_r = cos(θi − θr) − sinθi sinθr (1 − cosΔ); β from atan2 is accurate
        // at both ends of its range.
        let cos_2beta = (self.theta_i - self.theta_r).cos() - si * sr * vers;
        let beta = 0.5 * sin_2beta.atan2(cos_2beta);

        let (eta_i, eta_r) = if sin_2beta > 0.0 {
            (si_n.atan2(ci_n), sr_n.atan2(cr_n))
        } else {
            // β = 0 (retro-reflection): s_l = s_in (spec §3). Then η_i = 0 and
            // cos η_r = s_out·s_in = −cosΔ, sin η_r = p_out·s_in = cosθr sinΔ.
            (0.0, (cr * sd).atan2(-delta.cos()))
        };

        // Half vector s = w_i + w_r (unnormalized): θN = atan2(|s_xy|, s_z), s_z = cosθi + cosθr.
        // |s_xy|² = sin²θi + sin²θr + 2 sinθi sinθr cosΔ = (sinθi − sinθr)² + 4 sinθi sinθr cos²(Δ/2)
        // with sinθi − sinθr = 2 cos v sin u, v = (θi + θr)/2, u = (θi − θr)/2: a sum of two
        // squares (no cancellation, so θN keeps full relative accuracy near specular and toward
        // grazing), symmetric in the two directions, and a function of Δ like β and η. cos v is
        // sin(π/2 − v), from the complements π/2 − θ (accurate when both directions graze).
        let complement = |t: f64| (FRAC_PI_2 - t) + PIO2_LO;
        let cos_v = (0.5 * (complement(self.theta_i) + complement(self.theta_r))).sin();
        let sin_u = (0.5 * (self.theta_i - self.theta_r)).sin();
        let half_cos = (0.5 * delta).cos();
        let rho = 2.0 * (cos_v * sin_u).hypot((si * sr).sqrt() * half_cos);
        let sz = ci + cr;
        let theta_n = rho.atan2(sz);
        // Below rounding level of |s_xy| the facet is the macro normal (θN = 0) and ΦN = 0 (spec §1).
        // The azimuths themselves carry rounding errors of order ulp(|φ|) (e.g. φ + π, or a
        // rotation by several turns), which tilt a specular half vector sideways by as much:
        // the rounding level scales with max(1, |φi|, |φr|).
        let phi_scale = self.phi_i.abs().max(self.phi_r.abs()).max(1.0);
        let phi_n = if rho > 8.0 * f64::EPSILON * (si + sr) * phi_scale {
            // Angle between the plane (z, h) and the plane of incidence, folded into [0, π/2]:
            // from the components of s along the plane of incidence,
            // s∥ = sinθi + sinθr cosΔ = 2 cos v sin u + 2 sinθr cos²(Δ/2), and across it,
            // s⊥ = sinθr sinΔ.
            let along = 2.0 * (cos_v * sin_u + sr * half_cos * half_cos);
            let across = sr * sd;
            let d = across.abs().atan2(along.abs());
            d.clamp(0.0, FRAC_PI_2)
        } else {
            0.0
        };

        Some(AngleVariables {
            theta_i: self.theta_i,
            theta_r: self.theta_r,
            beta,
            theta_n,
            phi_n,
            eta_i,
            eta_r,
        })
    }
}

/// Unit vector `(sinθ cosφ, sinθ sinφ, cosθ)` (spec §1).
pub fn direction(theta: f64, phi: f64) -> [f64; 3] {
    let (st, ct) = theta.sin_cos();
    let (sp, cp) = phi.sin_cos();
    [st * cp, st * sp, ct]
}

/// The angle variables the model is written in (radians).
///
/// This is the "angle-variable entry point" of spec §5: [`crate::Material::evaluate_angles`]
/// takes one directly, so a caller can set θN as a free roughness variable at in-plane specular
/// geometry, as the paper's Fig. 2 does. [`Geometry::angle_variables`] computes it from two
/// directions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AngleVariables {
    /// Incidence zenith angle θi (eq. 1).
    pub theta_i: f64,
    /// Viewing zenith angle θr (eq. 1).
    pub theta_r: f64,
    /// Local incidence angle on the facet, β = acos(w_i·h) (eqs. 1, 3, 11).
    pub beta: f64,
    /// Facet-normal zenith angle θN = acos(h·z) (eqs. 1–4).
    pub theta_n: f64,
    /// Facet-normal azimuth relative to the plane of incidence, folded into [0, π/2] (eq. 3).
    pub phi_n: f64,
    /// Signed rotation from the incident beam's s axis to the facet's s axis (eq. 11).
    pub eta_i: f64,
    /// Signed rotation from the reflected beam's s axis to the facet's s axis (eq. 11).
    pub eta_r: f64,
}

impl AngleVariables {
    /// Angle variables of an in-plane specular configuration with the facet tilted by θN, as in
    /// the paper's Fig. 2: `θi = θr = β = theta`, `ΦN = 0`, `η_i = η_r = 0`.
    pub fn in_plane_specular(theta: f64, theta_n: f64) -> Self {
        Self {
            theta_i: theta,
            theta_r: theta,
            beta: theta,
            theta_n,
            phi_n: 0.0,
            eta_i: 0.0,
            eta_r: 0.0,
        }
    }
}
