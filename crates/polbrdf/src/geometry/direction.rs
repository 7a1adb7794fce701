//! Scattering geometry (docs/model.md §1): directions and one illumination/viewing geometry.
//!
//! Directions point **away** from the surface: `w = (sinθ cosφ, sinθ sinφ, cosθ)`, toward the
//! source (`w_i`) or the detector (`w_r`). The facet normal is the half vector
//! `h = unit(w_i + w_r)`.

use crate::error::{AngleProblem, Error, Result};
use crate::geometry::angles::AngleVariables;
use std::f64::consts::{FRAC_PI_2, PI};

/// One illumination/viewing geometry in radians (the θi, Φi, θr, Φr of eq. 1).
///
/// Construct it with [`Geometry::new`] or [`Geometry::from_degrees`], which reject NaN/∞ and
/// zenith angles outside `[0, π]`. Zenith angles `≥ π/2` are valid: such a direction is at or
/// below the horizon and the model returns the zero matrix there (docs/model.md §1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Geometry {
    theta_i: f64,
    phi_i: f64,
    theta_r: f64,
    phi_r: f64,
}

/// Checks a zenith angle given in radians or, with `degrees`, in degrees; returns it with −0.0
/// turned into +0.0.
pub(crate) fn check_zenith(
    name: &'static str,
    value: f64,
    degrees: bool,
    index: Option<usize>,
) -> Result<f64> {
    let max = if degrees { 180.0 } else { PI };
    let problem = if !value.is_finite() {
        AngleProblem::NotFinite
    } else if !(0.0..=max).contains(&value) {
        AngleProblem::ZenithRange
    } else {
        return Ok(value + 0.0);
    };
    Err(Error::InvalidAngle {
        name,
        value,
        degrees,
        index,
        problem,
    })
}

/// Checks that an azimuth is finite.
pub(crate) fn check_azimuth(
    name: &'static str,
    value: f64,
    degrees: bool,
    index: Option<usize>,
) -> Result<f64> {
    let max = if degrees {
        crate::MAX_AZIMUTH_DEG
    } else {
        crate::MAX_AZIMUTH_DEG.to_radians()
    };
    if value.is_finite() && value.abs() <= max {
        Ok(value)
    } else {
        Err(Error::InvalidAngle {
            name,
            value,
            degrees,
            index,
            problem: if value.is_finite() {
                AngleProblem::AzimuthTooLarge
            } else {
                AngleProblem::NotFinite
            },
        })
    }
}

/// The names of the four angles, in radians and in degrees.
const NAMES: [[&str; 4]; 2] = [
    ["theta_i", "phi_i", "theta_r", "phi_r"],
    ["theta_i_deg", "phi_i_deg", "theta_r_deg", "phi_r_deg"],
];

impl Geometry {
    /// A geometry from zenith and azimuth angles in radians.
    ///
    /// # Errors
    /// [`Error::InvalidAngle`] for NaN/∞ or a zenith angle outside `[0, π]`.
    pub fn new(theta_i: f64, phi_i: f64, theta_r: f64, phi_r: f64) -> Result<Self> {
        Self::checked([theta_i, phi_i, theta_r, phi_r], false, None)
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

    /// Validates the four angles, given in radians or (with `degrees`) in degrees; errors name
    /// the angle as given (`theta_i` or `theta_i_deg`) with its value in that unit.
    pub(crate) fn checked(angles: [f64; 4], degrees: bool, index: Option<usize>) -> Result<Self> {
        let names = NAMES[usize::from(degrees)];
        let [ti, pi, tr, pr] = angles;
        let ti = check_zenith(names[0], ti, degrees, index)?;
        let pi = check_azimuth(names[1], pi, degrees, index)?;
        let tr = check_zenith(names[2], tr, degrees, index)?;
        let pr = check_azimuth(names[3], pr, degrees, index)?;
        Ok(if degrees {
            Self::new_unchecked(
                ti.to_radians(),
                pi.to_radians(),
                tr.to_radians(),
                pr.to_radians(),
            )
        } else {
            Self::new_unchecked(ti, pi, tr, pr)
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
        Self::checked([theta_i_deg, phi_i_deg, theta_r_deg, phi_r_deg], true, None)
    }

    /// In-plane specular geometry: `θr = θi`, `φr = φi + π` (docs/model.md §1).
    ///
    /// # Errors
    /// As [`Geometry::new`].
    pub fn specular(theta: f64, phi: f64) -> Result<Self> {
        Self::new(theta, phi, theta, phi + PI)
    }

    /// Retro-reflection (backscatter, zero bistatic angle): `θr = θi`, `φr = φi` (docs/model.md §1, §6).
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

    /// True when both directions are strictly above the horizon (`θ < π/2`, docs/model.md §1).
    pub fn is_above_horizon(&self) -> bool {
        self.theta_i < FRAC_PI_2 && self.theta_r < FRAC_PI_2
    }

    /// The same geometry with both azimuths turned by `delta` (rad). The model is invariant
    /// under this rotation (docs/model.md §7).
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

    /// Unit vector toward the source, `w_i` (docs/model.md §1).
    pub fn w_i(&self) -> [f64; 3] {
        direction(self.theta_i, self.phi_i)
    }

    /// Unit vector toward the detector, `w_r` (docs/model.md §1).
    pub fn w_r(&self) -> [f64; 3] {
        direction(self.theta_r, self.phi_r)
    }

    /// The model's angle variables for this geometry (θN, β, ΦN of eqs. 1–3 and the signed
    /// Priest–Meier rotation angles η_i, η_r of eq. 11), or `None` when a direction is at or
    /// below the horizon. Closed forms of [`crate::geometry::angles`], accurate near β → 0 and
    /// θ → 0 (docs/model.md §9.2).
    pub fn angle_variables(&self) -> Option<AngleVariables> {
        self.is_above_horizon()
            .then(|| AngleVariables::of(self.theta_i, self.phi_i, self.theta_r, self.phi_r))
    }
}

/// Unit vector `(sinθ cosφ, sinθ sinφ, cosθ)` (docs/model.md §1).
pub fn direction(theta: f64, phi: f64) -> [f64; 3] {
    let (st, ct) = theta.sin_cos();
    let (sp, cp) = phi.sin_cos();
    [st * cp, st * sp, ct]
}

#[cfg(test)]
mod azimuth_bound {
    use super::*;

    #[test]
    fn azimuths_beyond_the_bound_lose_their_digits_and_are_refused() {
        for phi in [1e17, -1e300, 1.000001e8] {
            let e = Geometry::from_degrees(30.0, phi, 30.0, 180.0).unwrap_err();
            assert!(
                matches!(
                    e,
                    Error::InvalidAngle {
                        problem: AngleProblem::AzimuthTooLarge,
                        ..
                    }
                ),
                "{e}"
            );
            assert!(Geometry::new(0.5, 0.0, 0.5, phi).is_err());
        }
        // At the bound the angle is still exact to 1e-8° (1e8 = 277777·360 + 280).
        let g = Geometry::from_degrees(30.0, 0.0, 30.0, -crate::MAX_AZIMUTH_DEG).unwrap();
        let near = Geometry::from_degrees(30.0, 0.0, 30.0, -280.0).unwrap();
        assert!((g.phi_r().sin() - near.phi_r().sin()).abs() < 1e-9);
        assert!(Geometry::new(0.5, crate::MAX_AZIMUTH_DEG.to_radians(), 0.5, 0.0).is_ok());
    }
}
