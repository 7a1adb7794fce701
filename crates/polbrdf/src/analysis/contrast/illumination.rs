//! The light falling on both surfaces of a collimated contrast: the source's direction and its
//! input Stokes vector, checked and normalized to `S0 = 1`.

use crate::error::{AngleProblem, Error, Result};
use crate::geometry::Geometry;
use crate::optics::stokes::Stokes;
use std::f64::consts::{FRAC_PI_2, PI};

/// The light falling on both surfaces: direction toward the source and input Stokes vector.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Illumination {
    theta_i: f64,
    phi_i: f64,
    stokes: Stokes,
}

impl Illumination {
    /// Light from `(theta_i, phi_i)` (radians; `0 ≤ θi < π/2`) with input Stokes vector
    /// `stokes`, which is normalized to `S0 = 1` (results are per unit incident irradiance).
    ///
    /// # Errors
    /// [`Error::InvalidAngle`] (`sun_zenith`, `sun_azimuth`) for a source at or below the
    /// horizon, a negative zenith or a non-finite angle; [`Error::InvalidParameter`] (`stokes`)
    /// for a non-finite vector, `S0 ≤ 0` or a degree of polarization above 1.
    pub fn new(theta_i: f64, phi_i: f64, stokes: Stokes) -> Result<Self> {
        Self::named(theta_i, phi_i, stokes, ("sun_zenith", "sun_azimuth"), false)
    }

    /// As [`Illumination::new`] with the angles in degrees; errors name `sun_zenith_deg` and
    /// `sun_azimuth_deg` and give the values in degrees.
    ///
    /// # Errors
    /// As [`Illumination::new`].
    pub fn from_degrees(sun_zenith_deg: f64, sun_azimuth_deg: f64, stokes: Stokes) -> Result<Self> {
        Self::named(
            sun_zenith_deg.to_radians(),
            sun_azimuth_deg.to_radians(),
            stokes,
            ("sun_zenith_deg", "sun_azimuth_deg"),
            true,
        )
    }

    fn named(
        theta_i: f64,
        phi_i: f64,
        stokes: Stokes,
        (zenith, azimuth): (&'static str, &'static str),
        degrees: bool,
    ) -> Result<Self> {
        let unit = if degrees { 180.0 / PI } else { 1.0 };
        if !theta_i.is_finite() || !(0.0..FRAC_PI_2).contains(&theta_i) {
            return Err(Error::InvalidAngle {
                name: zenith,
                value: theta_i * unit,
                degrees,
                index: None,
                problem: AngleProblem::SourceBelowHorizon,
            });
        }
        if !(phi_i.is_finite() && phi_i.abs() <= crate::MAX_AZIMUTH_DEG.to_radians()) {
            return Err(Error::InvalidAngle {
                name: azimuth,
                value: phi_i * unit,
                degrees,
                index: None,
                problem: if phi_i.is_finite() {
                    AngleProblem::AzimuthTooLarge
                } else {
                    AngleProblem::NotFinite
                },
            });
        }
        Ok(Self {
            theta_i: theta_i + 0.0,
            phi_i,
            stokes: normalized_stokes(stokes)?,
        })
    }

    /// Zenith angle of the source (rad).
    pub fn theta_i(&self) -> f64 {
        self.theta_i
    }
    /// Azimuth of the source (rad).
    pub fn phi_i(&self) -> f64 {
        self.phi_i
    }
    /// The input Stokes vector, normalized to `S0 = 1`.
    pub fn stokes(&self) -> Stokes {
        self.stokes
    }
    /// The geometry for viewing direction `(theta_r, phi_r)` (rad; θr clamped into
    /// `[0, π/2]`).
    pub fn geometry(&self, theta_r: f64, phi_r: f64) -> Geometry {
        Geometry::new_unchecked(
            self.theta_i,
            self.phi_i,
            theta_r.clamp(0.0, FRAC_PI_2),
            phi_r,
        )
    }
}

/// Checks a Stokes vector and scales it to `S0 = 1`.
fn normalized_stokes(s: Stokes) -> Result<Stokes> {
    let bad = |value: f64, reason: &'static str| {
        Err(Error::InvalidParameter {
            name: "stokes",
            value,
            reason,
        })
    };
    if let Some(v) = s.0.iter().find(|v| !v.is_finite()) {
        return bad(*v, "every Stokes component must be finite");
    }
    let s0 = s.s0();
    if s0 <= 0.0 {
        return bad(s0, "S0 (the intensity) must be > 0");
    }
    let dop = s.dop();
    if dop > 1.0 + 1e-9 {
        return bad(
            dop,
            "degree of polarization sqrt(S1² + S2² + S3²)/S0 must be ≤ 1",
        );
    }
    Ok(Stokes(s.0.map(|v| v / s0)))
}
